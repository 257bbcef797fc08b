#include "core/segment/patient_input.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <string>

#include "core/face/face_landmarks.h"
#include "core/face/landmark_file.h"
#include "core/fields/constraint_set.h"
#include "core/io/mesh_io.h"
#include "core/mesh/mid_sagittal_plane.h"
#include "core/segment/ct_volume.h"
#include "core/segment/face_cuts.h"
#include "core/segment/head_frame.h"
#include "core/segment/voxel_grid.h"
#include "core/util/error.h"
#include "core/util/resources.h"
#include "tests/core/segment/phantom.h"
#include "tests/core/segment/pitched_ct.h"

namespace facehex {
namespace {
namespace fs = std::filesystem;

TEST(PatientInput, CtVolumesAreTheImageFormatsAndFolders) {
  for (const char* ct : {"head.mhd", "HEAD.MHA", "a/b/head.nii", "head.nii.gz", "head.nrrd", "head.nhdr"})
    EXPECT_TRUE(is_ct_input(ct)) << ct;
  for (const char* mesh : {"patient.vtu", "patient.vtk", "face.stl", "head.gz", ".mhd", "mhd"})
    EXPECT_FALSE(is_ct_input(mesh)) << mesh;
  EXPECT_TRUE(is_ct_input(fs::temp_directory_path().string()));  // a DICOM folder
}

TEST(PatientInput, AMeshFileIsReadCheckedAndOriented) {
  // Two tets sharing a face, both negatively oriented: flipped, and said so.
  VolumeMesh m =
      VolumeMesh::from_tets((Eigen::MatrixXd(5, 3) << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1).finished(),
                            (Eigen::MatrixXi(2, 4) << 0, 2, 1, 3, 0, 1, 2, 4).finished());
  const fs::path path = fs::temp_directory_path() / ("facehex-patient-input-" + std::to_string(::getpid()) + ".vtu");
  write_volume_mesh(path.string(), m);
  const PatientTetModel p = load_patient_model(path.string());
  fs::remove(path);
  EXPECT_TRUE(p.check.reoriented);
  EXPECT_EQ(p.mesh.num_cells(), 2);
  EXPECT_NEAR(p.check.volume, 2.0 / 6.0, 1e-12);
}

TEST(PatientInput, ACtIsSegmentedAndItsThresholdsAndCutsAreReturned) {
  const CtVolume ct = testing::ellipsoid_phantom();
  const fs::path path = fs::temp_directory_path() / ("facehex-patient-input-" + std::to_string(::getpid()) + ".mha");
  write_ct_volume(path.string(), ct);
  const SegmentOptions options = testing::phantom_options(ct);
  const PatientTetModel p = load_patient_model(path.string(), options);
  fs::remove(path);
  ASSERT_TRUE(p.segmentation);
  const TissueThresholds& thresholds = p.segmentation->thresholds;
  const FaceCuts& cuts = p.segmentation->cuts;
  EXPECT_NEAR(thresholds.skin, 500, 150);  // between air (0) and soft tissue (1000)
  EXPECT_GT(thresholds.bone, 1000);
  EXPECT_EQ(p.segmentation->options.tets.target_edge_length, options.tets.target_edge_length);  // as given
  EXPECT_EQ(p.segmentation->options.follow_scan_spacing, options.follow_scan_spacing);
  EXPECT_EQ(p.segmentation->options.coarsen_above_tets, options.coarsen_above_tets);
  EXPECT_GE(p.segmentation->edge_length, options.tets.target_edge_length);  // as made: the rules may lengthen it
  EXPECT_EQ(cuts.top_z, *options.cuts.top_z);                               // given cuts are used as given
  EXPECT_EQ(cuts.bottom_z, *options.cuts.bottom_z);
  EXPECT_EQ(cuts.posterior_y, *options.cuts.posterior_y);
  EXPECT_EQ(cuts.centre_x, *options.cuts.centre_x);
  const Eigen::Vector3d lo = p.mesh.V.colwise().minCoeff(), hi = p.mesh.V.colwise().maxCoeff();
  EXPECT_LE(hi.z(), cuts.top_z + 1e-6);
  EXPECT_GE(lo.z(), cuts.bottom_z - 1e-6);
  EXPECT_GE(lo.y(), cuts.posterior_y - 1e-6);  // the model lies in front of the posterior cut
  EXPECT_GT(p.mesh.num_cells(), 1000);
}

TEST(PatientInput, AHeadPitchedInTheScannerIsSegmentedAgainInTheFrameOfItsHardPalate) {
  // The Visible Human's CT (../shared, optional) with its chin raised by 10 degrees: in the CT's frame its lips are not
  // found; its hard palate says how far it is pitched, and the CT is segmented again in that frame, where they are.
  const std::string source = std::string(FACEHEX_SHARED_DIR) + "/data/ct/vhfemale-head.mha";
  if (!fs::exists(source)) GTEST_SKIP() << "no shared data at " << source;
  CtVolume ct = read_ct_volume(source);
  const std::optional<double> upright = build_patient_model(ct, SegmentOptions{}).cuts.palate_pitch;
  ASSERT_TRUE(upright);
  EXPECT_LT(std::abs(*upright), kMinHeadPitch);  // this head lies upright: its palate within a few degrees
  HeadTurn scan;                                 // from the upright CT to the pitched one
  scan.pitch = -10;
  scan.axis = Eigen::Vector2d(256, 256);
  scan.axis_z = 117;
  ct.intensity = turned_to_head_frame(ct.intensity, scan, 1.0,
                                      *std::min_element(ct.intensity.data.begin(), ct.intensity.data.end()));
  const fs::path path = fs::temp_directory_path() / ("facehex-pitched-" + std::to_string(::getpid()) + ".mha");
  write_ct_volume(path.string(), ct);
  const PatientTetModel p = load_patient_model(path.string());
  fs::remove(path);
  ASSERT_TRUE(p.segmentation);
  const FaceCuts& cuts = p.segmentation->cuts;
  ASSERT_TRUE(cuts.palate_pitch);
  EXPECT_NEAR(*cuts.palate_pitch, *upright + 10, 3.0);
  EXPECT_EQ(cuts.turn.pitch, *cuts.palate_pitch);
  EXPECT_NE(p.segmentation->repair.find("segmented again with the head pitched back by"), std::string::npos)
      << p.segmentation->repair;
  const FaceLandmarks l = find_face_landmarks(p.mesh.V, side_mask_of(p.mesh), landmark_options_for(p.mesh, "model"));
  check_plausible(l, "");
  // The profile read in the pitched frame: the nose tip in front of the lips, the chin below them.
  const HeadTurn frame = head_turn_of(l.plane);
  EXPECT_GT(frame.to_head(l.points.at("subnasale")).z(), frame.to_head(l.points.at("stomion")).z() + 10);
  EXPECT_GT(frame.to_head(l.points.at("stomion")).z(), frame.to_head(l.points.at("pogonion")).z() + 10);
}

TEST(PatientInput, AFaceFoundNeitherInTheCtsFrameNorPitchedBackIsAnErrorNamingBoth) {
  // The bundled CT with its chin lowered 25 degrees more, on its own grid (what turns out of the field of view is
  // lost): no nose stands out of its profile in the CT's frame, and pitched back by its palate's slope the field of
  // view's tilted ends leave a face whose landmarks are implausible. The error says both, and names the option.
  const CtVolume ct = testing::pitched_on_its_grid(read_ct_volume(default_ct()), testing::bundled_ct_pitch(25));
  const fs::path path = fs::temp_directory_path() / ("facehex-pitched-bundled-" + std::to_string(::getpid()) + ".mha");
  write_ct_volume(path.string(), ct);
  SegmentOptions options;
  options.tets.target_edge_length = 4.0;
  try {
    load_patient_model(path.string(), options);
    ADD_FAILURE() << "expected facehex::Error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no nose stands out"), std::string::npos) << what;
    EXPECT_NE(what.find("; nor with the head pitched back by"), std::string::npos) << what;
    EXPECT_NE(what.find("--head-pitch sets the pitch"), std::string::npos) << what;
  }
  // A pitch given is the only one tried.
  options.cuts.head_pitch = 0;
  try {
    load_patient_model(path.string(), options);
    ADD_FAILURE() << "expected facehex::Error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).find("nor with"), std::string::npos) << e.what();
  }
  fs::remove(path);
}

// The bundled CT pitched on its own grid by a few degrees either way (what turns out of the field of view is lost, as
// in a scan), too little for the hard palate to undo: its profile is read in the CT's frame, where the flat front that
// its field of view clipped the nose to leans by the pitch. Followed along its lean, the lips are found within 3 mm of
// the hand-placed ones (tests/data/landmarks) pitched with the CT. Measured behind an upright front, the plateau ended
// short of the cut's ends: at -5 degrees the lips were read 45-57 mm from them in a set that passed as plausible, at -8
// and +8 the set was refused.
TEST(PatientInput, TheBundledCtPitchedAFewDegreesHasItsLipsFoundBelowItsLeaningCut) {
  const CtVolume upright = read_ct_volume(default_ct());
  std::map<std::string, Eigen::Vector3d> reference;
  for (const NamedLandmark& l : read_landmark_file(std::string(FACEHEX_TEST_DATA_DIR) + "/landmarks/headsq.json"))
    reference[l.name] = l.position;
  SegmentOptions options;
  options.tets.target_edge_length = 4.0;
  for (const double pitch : {-8.0, -5.0, 8.0}) {
    const HeadTurn scan = testing::bundled_ct_pitch(pitch);  // from the upright CT to the pitched one
    const PatientModel m = build_patient_model(testing::pitched_on_its_grid(upright, scan), options);
    const FaceLandmarks l = find_face_landmarks(m.mesh.V, side_mask_of(m.mesh), landmark_options_for(m.mesh, "model"));
    EXPECT_FALSE(std::isnan(l.clipped_from)) << pitch;
    for (const char* name : {"subnasale", "labrale superius", "stomion", "labrale inferius"})
      EXPECT_LT((l.points.at(name) - scan.to_head(reference.at(name))).norm(), 3.0) << name << ", pitch " << pitch;
    EXPECT_NO_THROW(check_plausible(l, "")) << pitch;
    // The model lies within what the scan holds, below its tilted last slice: the top cut stays below where that
    // slice crosses the forehead's front (face_anatomy.h, rule 3b). Cut at the head's highest level less the margin,
    // the forehead's front at +8 degrees reached 1.8 mm beyond it.
    double highest = -std::numeric_limits<double>::infinity();
    for (int v = 0; v < m.mesh.num_vertices(); ++v)
      highest = std::max(highest, scan.to_model(m.mesh.V.row(v).transpose()).z());
    EXPECT_LT(highest, upright.intensity.geometry.upper(2) - 1.0) << pitch;
  }
}

// A head tilted towards a shoulder: a CT rolled by `degrees` about its front-to-back axis through `centre`, on its own
// grid (what turns out of the field of view is lost), and where a point of the upright CT lies in it.
struct RolledCt {
  Eigen::Matrix3d rotation;  // about +y: +x towards -z
  Eigen::Vector3d centre;
  RolledCt(double degrees, const Eigen::Vector3d& centre)
      : rotation(Eigen::AngleAxisd(degrees * M_PI / 180, Eigen::Vector3d::UnitY()).toRotationMatrix()),
        centre(centre) {}
  Eigen::Vector3d rolled(const Eigen::Vector3d& p) const { return centre + rotation * (p - centre); }
  CtVolume of(const CtVolume& upright) const {
    CtVolume ct = upright;
    ct.intensity = resample_mapped(
        upright.intensity, upright.intensity.geometry,
        [&](const Eigen::Vector3d& p) { return Eigen::Vector3d(centre + rotation.transpose() * (p - centre)); },
        *std::min_element(upright.intensity.data.begin(), upright.intensity.data.end()));
    return ct;
  }
};

// The model's mid-sagittal plane leans by `degrees` within `lean_tolerance` and passes within `tolerance` mm of every
// landmark of the mid-sagittal profile in `reference` rolled with the CT.
void expect_plane_through_rolled_profile(const PatientModel& m, const RolledCt& roll, double degrees,
                                         const std::string& reference, double lean_tolerance, double tolerance) {
  const std::optional<MidSagittalPlane> plane = mid_sagittal_plane(m.mesh, "model");
  ASSERT_TRUE(plane);
  EXPECT_NEAR(std::atan(plane->slope) * 180 / M_PI, degrees, lean_tolerance);
  static const std::set<std::string> kOnTheProfile = {"glabella",         "nasion",  "pronasale",        "subnasale",
                                                      "labrale superius", "stomion", "labrale inferius", "pogonion"};
  for (const NamedLandmark& l : read_landmark_file(std::string(FACEHEX_TEST_DATA_DIR) + "/landmarks/" + reference)) {
    if (!kOnTheProfile.count(l.name)) continue;
    const Eigen::Vector3d p = roll.rolled(l.position);
    EXPECT_LT(std::abs(plane->x_at(p.y(), p.z()) - p.x()), tolerance) << l.name << " in " << reference;
  }
}

// A level of a tilted head cuts its two sides at different heights. The bundled CT rolled 10 degrees: the plane
// measured on its levels leaned 3.4 degrees too far, agreed by too few of them to be taken, and the vertical plane
// through the nose put the lips 5-9 mm beside the profile; its sections' mirror lines turned by 2.6 degrees, which the
// head frame took for a turn (the upright CT's is under kMinHeadTurn: none).
TEST(PatientInput, TheBundledCtTiltedTowardsAShoulderHasItsMidSagittalPlaneThroughItsProfile) {
  const RolledCt roll(10, Eigen::Vector3d(100.8, 100.8, 69));
  SegmentOptions options;
  options.tets.target_edge_length = 4.0;
  const PatientModel m = build_patient_model(roll.of(read_ct_volume(default_ct())), options);
  expect_plane_through_rolled_profile(m, roll, 10, "headsq.json", 2.5, 4.0);
  EXPECT_EQ(m.cuts.turn.degrees, 0.0);
}

// The Visible Human's CT (../shared, optional) rolled 20 degrees, as far as the issue asks: on its levels, the plane
// lay 3-4 mm beside the profile along its whole height (rolled 10 degrees), and the sections' mirror lines turned
// 3 degrees beyond the upright CT's turn (-3.1 degrees, found on its sections).
TEST(PatientInput, TheVisibleHumanTiltedTowardsAShoulderHasItsMidSagittalPlaneThroughItsProfile) {
  const std::string source = std::string(FACEHEX_SHARED_DIR) + "/data/ct/vhfemale-head.mha";
  if (!fs::exists(source)) GTEST_SKIP() << "no shared data at " << source;
  const RolledCt roll(20, Eigen::Vector3d(255.5, 255.5, 116.5));
  const PatientModel m = build_patient_model(roll.of(read_ct_volume(source)), SegmentOptions{});
  expect_plane_through_rolled_profile(m, roll, 20, "vhfemale-head.json", 1.0, 3.5);
  EXPECT_NEAR(m.cuts.turn.degrees, -3.1, 1.0);
  // Its top cut tilts with it, 15 mm above the glabella (the scan holds the whole head); the bottom cut stays level,
  // since so tilted it would leave the scan, which starts 25 mm under the chin.
  const std::optional<MidSagittalPlane> plane = mid_sagittal_plane(m.mesh, "model");
  ASSERT_TRUE(plane && m.cuts.anatomy);
  EXPECT_NEAR(m.cuts.top_slope, -plane->slope, 0.01);  // the stored plane is in the CT's frame, turned
  EXPECT_NEAR(m.cuts.top_z_at(m.cuts.anatomy->glabella.x()) - m.cuts.anatomy->glabella.z(), 15, 1e-9);
  EXPECT_EQ(m.cuts.bottom_slope, 0.0);
}

TEST(PatientInput, AMeshFileHasNoSegmentation) {
  const fs::path path = fs::temp_directory_path() / ("facehex-patient-input-m-" + std::to_string(::getpid()) + ".vtu");
  write_volume_mesh(path.string(),
                    VolumeMesh::from_tets((Eigen::MatrixXd(4, 3) << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1).finished(),
                                          (Eigen::MatrixXi(1, 4) << 0, 1, 2, 3).finished()));
  const PatientTetModel p = load_patient_model(path.string());
  fs::remove(path);
  EXPECT_FALSE(p.segmentation);
}

TEST(PatientInput, AMissingCtIsReportedByName) {
  try {
    load_patient_model("/no/such/ct.mhd");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/no/such/ct.mhd"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace facehex
