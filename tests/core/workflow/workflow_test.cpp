// The workflow both front ends call: the constraint policy, the domains, the standard's checks, the exit policy.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/face/automatic_constraints.h"
#include "core/face/landmark_file.h"
#include "core/fields/constraint_set.h"
#include "core/io/mesh_io.h"
#include "core/mesh/ct_landmarks.h"
#include "core/mesh/hex_to_tets.h"
#include "core/mesh/sides.h"
#include "core/segment/ct_volume.h"
#include "core/segment/voxel_grid.h"
#include "core/standard/closed_domain.h"
#include "core/util/error.h"
#include "core/util/resources.h"
#include "core/workflow/patient_setup.h"
#include "core/workflow/standard_setup.h"
#include "core/workflow/transfer.h"
#include "tests/core/test_meshes.h"

namespace facehex {
namespace {
namespace fs = std::filesystem;

// A box of tets with the six sides labelled (the hex box's side_mask), which has no face to find landmarks on.
VolumeMesh tet_box() {
  const VolumeMesh hex = test::hex_box(3, 2, 3, 30, 10, 30);
  VolumeMesh tets = VolumeMesh::from_tets(hex.V, split_into_tets(hex).T);
  tets.point_data = hex.point_data;
  return tets;
}

class Workflow : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("facehex-workflow-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST_F(Workflow, AGivenConstraintFileWinsOverOneBesideTheModel) {
  write_volume_mesh(path("box.vtu"), tet_box());
  ConstraintSet beside = side_constraints();
  beside.constraints.pop_back();
  write_constraint_set(path("box.json"), beside);
  ConstraintSet given = side_constraints();
  given.constraints.resize(2);
  write_constraint_set(path("given.json"), given);

  const PatientSetup from_given = load_patient(path("box.vtu"), {}, path("given.json"), nullptr);
  EXPECT_EQ(from_given.constraints.constraints.size(), 2u);
  EXPECT_EQ(from_given.constraints_path, path("given.json"));
  EXPECT_EQ(from_given.source(), path("given.json"));

  const PatientSetup from_beside = load_patient(path("box.vtu"), {}, "", nullptr);
  EXPECT_EQ(from_beside.constraints.constraints.size(), side_constraints().constraints.size() - 1);
  EXPECT_EQ(from_beside.constraints_path, path("box.json"));
}

TEST_F(Workflow, ConstraintsJsonInTheFolderIsTheBundledLayout) {
  write_volume_mesh(path("patient.vtu"), tet_box());
  ConstraintSet set = side_constraints();
  set.constraints.resize(3);
  write_constraint_set(path("constraints.json"), set);
  const PatientSetup p = load_patient(path("patient.vtu"), {}, "", nullptr);
  EXPECT_EQ(p.constraints.constraints.size(), 3u);
  EXPECT_EQ(p.constraints_path, path("constraints.json"));
}

TEST_F(Workflow, WithoutAFileAModelWithSidesGetsItsSidesAndSaysWhyNoFeatures) {
  write_volume_mesh(path("box.vtu"), tet_box());
  const PatientSetup no_values = load_patient(path("box.vtu"), {}, "", nullptr);
  EXPECT_EQ(no_values.constraints.constraints.size(), side_constraints().constraints.size());
  EXPECT_TRUE(no_values.constraints_path.empty());
  EXPECT_FALSE(no_values.features_problem.empty());
  EXPECT_FALSE(no_values.landmarks.has_value());

  // A box has no face: the landmarks are not found, the sides stay, and the problem is the finder's message.
  std::map<std::string, double> values;
  for (const auto& spec : feature_specs()) values[spec.name] = 0.5;
  const PatientSetup box = load_patient(path("box.vtu"), {}, "", &values);
  EXPECT_EQ(box.constraints.constraints.size(), side_constraints().constraints.size());
  EXPECT_FALSE(box.features_problem.empty());
  EXPECT_NE(box.constraints_note.find(box.features_problem), std::string::npos);
}

// Without side labels nothing can be placed: the model opens with no constraints (the application's user places them
// with the plane) and features_problem says why (the command line stops on it).
TEST_F(Workflow, AModelWithoutSidesOrConstraintFileGetsNoConstraintsAndTheReason) {
  VolumeMesh box = tet_box();
  box.point_data.clear();
  write_volume_mesh(path("bare.vtu"), box);
  std::map<std::string, double> values;
  for (const auto& spec : feature_specs()) values[spec.name] = 0.5;
  const PatientSetup p = load_patient(path("bare.vtu"), {}, "", &values);
  EXPECT_TRUE(p.constraints.constraints.empty());
  EXPECT_TRUE(p.constraints_path.empty());
  EXPECT_NE(p.features_problem.find("side_mask"), std::string::npos) << p.features_problem;
  EXPECT_NE(p.constraints_note.find("no constraints"), std::string::npos) << p.constraints_note;
}

TEST_F(Workflow, ATetModelIsItsOwnDomainWithAllItsVerticesAsModelVertices) {
  const VolumeMesh box = tet_box();
  const TetDomain d = own_domain(box);
  EXPECT_EQ(d.hex_vertices, box.num_vertices());
  EXPECT_EQ(d.V, box.V);
  EXPECT_EQ(d.T, box.tets());
  EXPECT_EQ(d.side_mask.size(), box.num_vertices());
  const PatientSetup p = patient_from_mesh(box, "in memory", nullptr);
  EXPECT_EQ(p.domain.hex_vertices, box.num_vertices());
  EXPECT_TRUE(p.constraints_path.empty());
}

// A model whose openings were closed by plugs (close_openings) is written with its own point data, the plugs' inner
// vertices on no side.
TEST_F(Workflow, TheParameterizedModelKeepsTheModelsPointDataWithItsPlugs) {
  // A tunnel from back to front through the middle column of the box.
  VolumeMesh model = test::tet_box_without(3, 2, 3, 30, 10, 30, [](int i, int, int k) { return i == 1 && k == 1; });
  CtLandmarks found;
  found.stomion = CtLandmark{Eigen::Vector3d(15, 10, 12), false};
  set_ct_landmarks(model, found);
  const TetDomain closed = close_openings(own_domain(model), "the model's own tets");
  ASSERT_EQ(closed.closed_openings, 1);
  const ModelParameterization p =
      parameterize_model(closed.V, closed.T, closed.side_mask, side_constraints(), "box", HarmonicFieldsOptions{});
  const VolumeMesh written = parameterized_tet_mesh(p, &model);
  ASSERT_EQ(written.point_data.count(kSideMaskArray), 1u);
  const Eigen::MatrixXd& mask = written.point_data.at(kSideMaskArray);
  ASSERT_EQ(mask.rows(), closed.V.rows());
  EXPECT_EQ(mask.topRows(model.num_vertices()), model.point_data.at(kSideMaskArray));
  EXPECT_TRUE(mask.bottomRows(closed.V.rows() - model.num_vertices()).isZero());
  // The landmarks read in the CT go with the model, so that running the written model finds them again.
  const std::optional<CtLandmarks> kept = ct_landmarks(written, "written");
  ASSERT_TRUE(kept.has_value());
  ASSERT_TRUE(kept->stomion.has_value());
  EXPECT_EQ(kept->stomion->point, found.stomion->point);
  // A model of other vertices lends none.
  VolumeMesh other = model;
  other.V.array() += 1;
  EXPECT_EQ(parameterized_tet_mesh(p, &other).point_data.count(kSideMaskArray), 0u);
  EXPECT_TRUE(parameterized_tet_mesh(p, &other).field_data.empty());
}

// An object the segmentation found on the skin (core/segment/skin_objects.h) goes with the patient's landmarks and is
// named in the note both front ends show.
TEST_F(Workflow, AnObjectOnTheSkinTheModelCarriesIsNamedInTheNote) {
  VolumeMesh model = read_volume_mesh(resource_dir() + "/patients/headsq/patient.vtu");
  const std::map<std::string, double> values = feature_values(read_constraint_set(default_standard().constraints));
  write_volume_mesh(path("bare.vtu"), model);
  const PatientSetup bare = load_patient(path("bare.vtu"), {}, "", &values);
  ASSERT_TRUE(bare.landmarks) << bare.features_problem;
  EXPECT_TRUE(bare.landmarks->skin_objects.empty());
  EXPECT_EQ(bare.constraints_note.find("an object lies"), std::string::npos) << bare.constraints_note;

  // Above the model's top: it changes no landmark, and is still listed.
  CtLandmarks found = ct_landmarks(model, "patient.vtu").value_or(CtLandmarks{});
  found.skin_objects = {{300, 320, 4, 4, {{295, 180}, {325, 175}}}};
  set_ct_landmarks(model, found);
  write_volume_mesh(path("strapped.vtu"), model);
  const PatientSetup strapped = load_patient(path("strapped.vtu"), {}, "", &values);
  ASSERT_TRUE(strapped.landmarks) << strapped.features_problem;
  ASSERT_EQ(strapped.landmarks->skin_objects.size(), 1u);
  EXPECT_NE(
      strapped.constraints_note.find("an object lies on the skin's front from z = 300.0 to 320.0 mm, 4.0 mm thick"),
      std::string::npos)
      << strapped.constraints_note;
  EXPECT_EQ(strapped.landmarks->points, bare.landmarks->points);
}

TEST_F(Workflow, AStandardMustBeHexDominantAndItsDomainKindKnown) {
  write_volume_mesh(path("tets.vtu"), tet_box());
  write_constraint_set(path("tets.json"), side_constraints());
  EXPECT_THROW(load_standard(path("tets.vtu")), Error);
  const VolumeMesh hex = test::hex_box(3, 2, 3, 30, 10, 30);
  EXPECT_THROW(standard_domain(hex, "open"), Error);
  EXPECT_NO_THROW(check_standard_domain_kind("closed"));
  EXPECT_NO_THROW(check_standard_domain_kind("auxiliary"));
  EXPECT_THROW(check_standard_domain_kind("open"), Error);
  const TetDomain aux = standard_domain(hex, "auxiliary");
  EXPECT_EQ(aux.hex_vertices, hex.num_vertices());
}

// The Visible Human's CT (../shared, optional) as scans that end across the head would hold it, made from the file:
// cropped behind the face at y 290 mm (20 mm in front of the tragi, the ears out of the scan) it is meshed in front of
// where the scan ends, its landmarks found as on the whole scan (within 3 mm of the hand-placed ones, the tragi
// unseen); cropped to x 195-330 mm, across the cheeks, it is refused, naming --posterior-cut.
TEST_F(Workflow, AHeadCtEndingBehindTheFaceIsMeshedInFrontOfWhereItEndsAndOneEndingAcrossTheCheeksIsRefused) {
  const std::string source = std::string(FACEHEX_SHARED_DIR) + "/data/ct/vhfemale-head.mha";
  if (!fs::exists(source)) GTEST_SKIP() << "no shared data at " << source;
  const CtVolume ct = read_ct_volume(source);
  const std::array<int, 3> dims = ct.intensity.geometry.dims;
  CtVolume behind = ct;
  behind.intensity = crop(ct.intensity, {0, 290, 0}, dims);
  write_ct_volume(path("behind.mha"), behind);
  std::map<std::string, double> values;  // any: the landmarks the features are placed at are what is checked
  for (const auto& spec : feature_specs()) values[spec.name] = 0.5;
  const PatientSetup p = load_patient(path("behind.mha"), {}, "", &values);
  ASSERT_TRUE(p.segmentation);
  EXPECT_TRUE(p.segmentation->cuts.posterior_at_scan_edge);
  EXPECT_NEAR(p.segmentation->cuts.posterior_y, 290 + FaceCutOptions{}.border_margin, 0.5);
  ASSERT_TRUE(p.landmarks) << p.features_problem;
  for (const NamedLandmark& placed :
       read_landmark_file(std::string(FACEHEX_TEST_DATA_DIR) + "/landmarks/vhfemale-head.json")) {
    const auto found = p.landmarks->points.find(placed.name);
    if (placed.name.rfind("tragus", 0) == 0) {
      EXPECT_EQ(found, p.landmarks->points.end()) << placed.name << " is not in the scan";
      continue;
    }
    ASSERT_NE(found, p.landmarks->points.end()) << placed.name;
    EXPECT_LT((found->second - placed.position).norm(), 3.0) << placed.name;
  }

  CtVolume across = ct;
  across.intensity = crop(ct.intensity, {195, 0, 0}, {331, dims[1], dims[2]});
  write_ct_volume(path("across.mha"), across);
  try {
    load_patient(path("across.mha"), {}, "", &values);
    FAIL() << "a scan ending across the cheeks was segmented";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the scan ends across the head"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--posterior-cut"), std::string::npos) << e.what();
  }
}

// A landmark file placed on a model's scan (a 3D Slicer file, in the scan's LPS frame, with the patient's sides) is
// read through the scan frame the model carries: on the bundled patient model given a DICOM-like frame (a half turn
// about the vertical axis and an offset), the Slicer file of its found landmarks gives them back where they were
// found, under the model's names; the same points written without the frame lie mirrored, off the skin: refused.
TEST_F(Workflow, AGivenSlicerFileIsReadThroughTheModelsScanFrame) {
  std::map<std::string, double> values;
  for (const auto& spec : feature_specs()) values[spec.name] = 0.5;
  VolumeMesh model = read_volume_mesh(default_patient().mesh);
  ScanFrame frame;
  frame.rotation = Eigen::Vector3d(-1, -1, 1).asDiagonal();
  frame.translation = Eigen::Vector3d(120, 140, -60);
  set_scan_frame(model, frame);
  write_volume_mesh(path("framed.vtu"), model);
  const PatientSetup found = load_patient(path("framed.vtu"), {}, "", &values);
  ASSERT_TRUE(found.landmarks) << found.features_problem;
  write_landmark_file(path("placed.mrk.json"), named_landmarks(*found.landmarks), frame);
  write_landmark_file(path("unframed.mrk.json"), named_landmarks(*found.landmarks));
  const PatientSetup given = load_patient(path("framed.vtu"), {}, "", &values, {}, path("placed.mrk.json"));
  ASSERT_TRUE(given.landmarks) << given.features_problem;
  EXPECT_TRUE(given.landmarks->given);
  for (const auto& [name, x] : found.landmarks->points) {
    ASSERT_TRUE(given.landmarks->points.count(name)) << name;
    EXPECT_LT((given.landmarks->points.at(name) - x).norm(), 1e-9) << name;
  }
  const PatientSetup mirrored = load_patient(path("framed.vtu"), {}, "", &values, {}, path("unframed.mrk.json"));
  EXPECT_FALSE(mirrored.landmarks);
  EXPECT_NE(mirrored.features_problem.find("mm from the model's skin"), std::string::npos) << mirrored.features_problem;
}

TEST(ExitCode, ZeroOnlyWhenNoCellIsInvertedOrFlat) {
  QualitySummary q;
  q.cells = 10;
  EXPECT_EQ(exit_code(q), 0);
  q.inverted = 1;
  EXPECT_EQ(exit_code(q), kExitUnusableCells);
  q.inverted = 0;
  q.degenerate = 2;
  EXPECT_EQ(exit_code(q), kExitUnusableCells);
  EXPECT_EQ(kExitUnusableCells, 3);
}

}  // namespace
}  // namespace facehex
