#include "core/segment/soft_tissue.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/face/face_landmarks.h"
#include "core/face/landmark_file.h"
#include "core/fields/constraint_set.h"
#include "core/mesh/ct_landmarks.h"
#include "core/mesh/mid_sagittal_plane.h"
#include "core/mesh/sides.h"
#include "core/mesh/skin_points.h"
#include "core/segment/head_frame.h"
#include "core/util/error.h"
#include "core/util/resources.h"
#include "tests/core/segment/phantom.h"

namespace facehex {
namespace {

// Edge-connected pieces of a set of triangles.
int pieces(const std::vector<std::array<int, 3>>& faces) {
  std::map<std::pair<int, int>, std::vector<int>> by_edge;
  for (size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) by_edge[std::minmax(faces[f][k], faces[f][(k + 1) % 3])].push_back(static_cast<int>(f));
  std::vector<int> parent(faces.size());
  for (size_t f = 0; f < faces.size(); ++f) parent[f] = static_cast<int>(f);
  std::function<int(int)> root = [&](int f) { return parent[f] == f ? f : parent[f] = root(parent[f]); };
  for (const auto& [edge, fs] : by_edge)
    for (int f : fs) parent[root(f)] = root(fs[0]);
  std::set<int> roots;
  for (size_t f = 0; f < faces.size(); ++f) roots.insert(root(static_cast<int>(f)));
  return static_cast<int>(roots.size());
}

std::vector<std::array<int, 3>> faces_of(const PatientModel& m, int side) {
  std::vector<std::array<int, 3>> out;
  for (int f = 0; f < m.boundary_faces.rows(); ++f)
    if (side < 0 || m.boundary_sides(f) == side)
      out.push_back({m.boundary_faces(f, 0), m.boundary_faces(f, 1), m.boundary_faces(f, 2)});
  return out;
}

int euler_characteristic(const std::vector<std::array<int, 3>>& faces) {
  std::set<int> vertices;
  std::set<std::pair<int, int>> edges;
  for (const auto& f : faces)
    for (int k = 0; k < 3; ++k) vertices.insert(f[k]), edges.insert(std::minmax(f[k], f[(k + 1) % 3]));
  return static_cast<int>(vertices.size() - edges.size() + faces.size());
}

// Everything a patient model promises: positive tets, one closed solid with a ball's boundary, six one-piece sides,
// a side bit on every boundary vertex and none inside.
void expect_valid_patient(const PatientModel& m) {
  ASSERT_TRUE(m.mesh.is_tet_mesh());
  for (int t = 0; t < m.mesh.num_cells(); ++t) {
    const Eigen::Vector3d p0 = m.mesh.V.row(m.mesh.C(t, 0)), p1 = m.mesh.V.row(m.mesh.C(t, 1)),
                          p2 = m.mesh.V.row(m.mesh.C(t, 2)), p3 = m.mesh.V.row(m.mesh.C(t, 3));
    ASSERT_GT((p1 - p0).dot((p2 - p0).cross(p3 - p0)), 0) << "tet " << t;
  }
  const auto all = faces_of(m, -1);
  EXPECT_EQ(pieces(all), 1);
  EXPECT_EQ(euler_characteristic(all), 2);
  for (int s = 0; s < kNumSides; ++s) {
    const auto side = faces_of(m, s);
    EXPECT_FALSE(side.empty()) << kSideNames[s];
    EXPECT_EQ(pieces(side), 1) << kSideNames[s];
  }
  ASSERT_TRUE(m.mesh.point_data.count(kSideMaskArray));
  const Eigen::MatrixXd& mask = m.mesh.point_data.at(kSideMaskArray);
  ASSERT_EQ(mask.rows(), m.mesh.num_vertices());
  std::vector<char> on_boundary(m.mesh.num_vertices(), 0);
  for (const auto& f : all)
    for (int v : f) on_boundary[v] = 1;
  for (int v = 0; v < m.mesh.num_vertices(); ++v) {
    const int bits = static_cast<int>(mask(v, 0));
    if (on_boundary[v])
      EXPECT_GT(bits, 0) << "boundary vertex " << v << " has no side";
    else
      EXPECT_EQ(bits, 0) << "interior vertex " << v << " has a side";
  }
}

TEST(SoftTissue, PhantomGivesOneShellWithSixSides) {
  const CtVolume ct = testing::ellipsoid_phantom();
  const PatientModel m = build_patient_model(ct, testing::phantom_options(ct));
  EXPECT_NEAR(m.thresholds.skin, 500, 150);
  EXPECT_GT(m.thresholds.bone, 1000);
  EXPECT_LT(m.thresholds.bone, 2000);
  expect_valid_patient(m);
  // The shell is the 10 mm soft-tissue layer: the model stays between the two ellipsoids.
  const Eigen::Vector3d c = testing::phantom_centre(ct), head(60, 75, 70), bone = head.array() - 10;
  for (int v = 0; v < m.mesh.num_vertices(); ++v) {
    const Eigen::Vector3d p = Eigen::Vector3d(m.mesh.V.row(v).transpose()) - c;
    EXPECT_LT(p.cwiseQuotient(head * 1.05).squaredNorm(), 1.0) << "vertex " << v << " outside the skin";
    EXPECT_GT(p.cwiseQuotient(bone * 0.95).squaredNorm(), 1.0) << "vertex " << v << " inside the bone";
    EXPECT_GE(p.y(), -0.5) << "vertex " << v << " behind the posterior cut";
  }
}

TEST(SoftTissue, AWiderFieldOfViewGivesTheSameModel) {
  // The phantom with 60 mm more air on each side in x and y (a scan's field of view is often several times the head's
  // section): the segmentation works on the body's box, so the model is the same, vertex for vertex.
  const CtVolume ct = testing::ellipsoid_phantom();
  CtVolume wide = ct;
  GridGeometry& g = wide.intensity.geometry;
  const int pad = 30;  // voxels of 2 mm
  g.dims[0] += 2 * pad, g.dims[1] += 2 * pad;
  g.origin -= Eigen::Vector3d(pad, pad, 0) * 2.0;
  wide.intensity.data.assign(g.size(), 0.0f);
  const GridGeometry& o = ct.intensity.geometry;
  for (int k = 0; k < o.dims[2]; ++k)
    for (int j = 0; j < o.dims[1]; ++j)
      for (int i = 0; i < o.dims[0]; ++i) wide.intensity(i + pad, j + pad, k) = ct.intensity(i, j, k);
  SegmentOptions options = testing::phantom_options(ct);
  options.skin_threshold = 500;  // the air added would move the histogram's thresholds
  options.bone_threshold = 1500;
  const PatientModel a = build_patient_model(ct, options), b = build_patient_model(wide, options);
  ASSERT_EQ(a.mesh.num_vertices(), b.mesh.num_vertices());
  ASSERT_EQ(a.mesh.num_cells(), b.mesh.num_cells());
  EXPECT_EQ((a.mesh.V - b.mesh.V).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(a.mesh.C, b.mesh.C);
}

TEST(SoftTissue, RealCtMakesASixSidedModel) {
  // The bundled headsq CT (resources/ct/headsq).
  const PatientModel m = build_patient_model(read_ct_volume(default_ct()));
  // The data's README: skin at about 500, bone at about 1150 (file units).
  EXPECT_NEAR(m.thresholds.skin, 550, 150);
  EXPECT_NEAR(m.thresholds.bone, 1150, 100);
  // Its slices are 3.2 mm apart in x and y: the tets follow the scan (a face of this size would keep the paper's 2 mm).
  EXPECT_NEAR(m.edge_length, 3.2, 1e-6);
  EXPECT_EQ(m.edge_length_rule, "the CT's coarsest voxel spacing");
  expect_valid_patient(m);
  // The model carries the CT's mid-sagittal plane, for the landmark finder.
  const std::optional<MidSagittalPlane> plane = mid_sagittal_plane(m.mesh, "model");
  ASSERT_TRUE(plane && m.cuts.anatomy);
  EXPECT_EQ(plane->x, m.cuts.centre_x);
  EXPECT_LT(std::abs(m.cuts.anatomy->roll_degrees), 5.0);  // upright: the plane is vertical
  EXPECT_EQ(plane->slope, 0.0);
  // And the skin at the working spacing (1 mm here, the model's edges 3.2 mm): several times as many points as the
  // model has skin vertices, over the same extent.
  const std::optional<Eigen::MatrixXd> skin = skin_points(m.mesh, "model");
  ASSERT_TRUE(skin);
  const Eigen::VectorXi mask = side_mask_of(m.mesh);
  std::vector<int> rows;
  for (int v = 0; v < m.mesh.num_vertices(); ++v)
    if (mask(v) & side_bit(W1)) rows.push_back(v);
  EXPECT_GT(skin->rows(), 3 * static_cast<Eigen::Index>(rows.size()));
  const Eigen::MatrixXd model_skin = m.mesh.V(rows, Eigen::all);
  EXPECT_LT((skin->colwise().minCoeff() - model_skin.colwise().minCoeff()).cwiseAbs().maxCoeff(), 1.0);
  EXPECT_LT((skin->colwise().maxCoeff() - model_skin.colwise().maxCoeff()).cwiseAbs().maxCoeff(), 1.0);
  // And the tragi, found in the CT behind the model's posterior cut: within 3 mm of the ones placed by hand.
  const std::optional<CtLandmarks> found_in_ct = ct_landmarks(m.mesh, "model");
  ASSERT_TRUE(found_in_ct);
  for (const NamedLandmark& placed :
       read_landmark_file(std::string(FACEHEX_TEST_DATA_DIR) + "/landmarks/headsq.json")) {
    if (placed.name != "tragus right" && placed.name != "tragus left") continue;
    const std::optional<CtLandmark>& found = found_in_ct->tragi[placed.name == "tragus right" ? 0 : 1];
    ASSERT_TRUE(found) << placed.name;
    EXPECT_FALSE(found->estimated) << placed.name;
    EXPECT_LT((found->point - placed.position).norm(), 3.0) << placed.name << " found at " << found->point.transpose();
    EXPECT_LT(found->point.y(), m.cuts.posterior_y) << placed.name;  // behind the model
  }
  // And the stomion, read in the CT's lips' slit, within the 3 mm bound.
  ASSERT_TRUE(found_in_ct->stomion);
  for (const NamedLandmark& placed : read_landmark_file(std::string(FACEHEX_TEST_DATA_DIR) + "/landmarks/headsq.json"))
    if (placed.name == "stomion") {
      EXPECT_LT((found_in_ct->stomion->point - placed.position).norm(), 3.0);
    }
  // And the eye corners, read in the CT: its closed slits are too shallow for its 3.2 mm slices, so all four are
  // estimated by adult proportions, as the hand-placed ones are, within the 5 mm bound of estimated landmarks.
  for (size_t c = 0; c < kEyeCornerNames.size(); ++c) {
    const std::optional<CtLandmark>& found = found_in_ct->eye_corners[c];
    ASSERT_TRUE(found) << kEyeCornerNames[c];
    EXPECT_TRUE(found->estimated) << kEyeCornerNames[c];
    for (const NamedLandmark& placed :
         read_landmark_file(std::string(FACEHEX_TEST_DATA_DIR) + "/landmarks/headsq.json"))
      if (placed.name == kEyeCornerNames[c]) {
        EXPECT_LT((found->point - placed.position).norm(), 5.0) << placed.name;
      }
  }
}

TEST(SoftTissue, ANoisyCtIsBlurredToADiagnosticCtsNoiseAndSegmentedAsTheQuietOne) {
  // The bundled CT with white noise of 80 file units added (8 % of its air to soft-tissue contrast, a low-dose or
  // cone-beam CT's): the noise widens the soft-tissue peak of the histogram and its tail rule puts the bone threshold
  // far above thin bone, through which the model then reaches with tunnels. Blurred first, it is segmented as the
  // CT without the noise is: the same thresholds, cuts and anatomy within a voxel or two.
  SegmentOptions options;
  options.tets.target_edge_length = 4.0;  // the anatomy does not depend on it; TetGen is quicker
  const CtVolume quiet = read_ct_volume(default_ct());
  const PatientModel reference = build_patient_model(quiet, options);
  EXPECT_EQ(reference.noise.blur, 0);  // a diagnostic CT: left as it is
  EXPECT_GT(reference.noise.sigma, 0);
  EXPECT_LT(reference.noise.sigma, kDiagnosticNoise * reference.noise.contrast);
  // The quiet CT with white noise of 80 from `seed`.
  const auto noisy_ct = [&quiet](unsigned seed) {
    CtVolume noisy = quiet;
    std::mt19937 random(seed);
    std::normal_distribution<float> noise(0.0f, 80.0f);
    for (float& v : noisy.intensity.data) v += noise(random);
    return noisy;
  };
  for (const unsigned seed : {7u, 8u}) {
    const CtVolume noisy = noisy_ct(seed);
    EXPECT_GT(estimate_thresholds(noisy.intensity).bone, reference.thresholds.bone + 300);  // what the blur is for
    const PatientModel m = build_patient_model(noisy, options);
    expect_valid_patient(m);
    EXPECT_NEAR(m.noise.sigma, 80, 10) << seed;
    EXPECT_GT(m.noise.blur, 1.0) << seed;
    EXPECT_NEAR(m.noise.sigma_after, kDiagnosticNoise * m.noise.contrast, 1) << seed;
    EXPECT_NEAR(m.thresholds.skin, reference.thresholds.skin, 20) << seed;
    EXPECT_NEAR(m.thresholds.bone, reference.thresholds.bone, 40) << seed;
    EXPECT_NEAR(m.cuts.top_z, reference.cuts.top_z, 2.0) << seed;
    EXPECT_NEAR(m.cuts.bottom_z, reference.cuts.bottom_z, 2.0) << seed;
    EXPECT_NEAR(m.cuts.posterior_y, reference.cuts.posterior_y, 2.0) << seed;
    ASSERT_TRUE(m.cuts.anatomy && reference.cuts.anatomy);
    const FaceAnatomy &a = *reference.cuts.anatomy, &b = *m.cuts.anatomy;
    EXPECT_LT((a.pronasale - b.pronasale).norm(), 3.0) << seed;  // the middle of the clipped nose's plateau
    EXPECT_LT((a.nasion - b.nasion).norm(), 3.0) << seed;
    EXPECT_LT((a.menton - b.menton).norm(), 4.0) << seed;  // the chin's lowest bone voxel, of a 3.2 mm CT
    // Within a tenth of the quiet model's volume: no tissue behind the thin bone.
    EXPECT_NEAR(m.mesh.num_vertices(), reference.mesh.num_vertices(), 0.1 * reference.mesh.num_vertices()) << seed;
  }
  // Told not to blur, the segmentation takes the CT as it is (the bone threshold the noise raised).
  options.denoising_blur = 0;
  try {
    const PatientModel m = build_patient_model(noisy_ct(7), options);
    EXPECT_EQ(m.noise.sigma, 0);  // not measured
    EXPECT_GT(m.thresholds.bone, reference.thresholds.bone + 300);
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("tunnels"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("or lower --bone (thin bone below the bone threshold"), std::string::npos)
        << e.what();
  }
}

// Dental-metal streaks in the axial slices within 8 mm of `stomion`'s height (tapered): rays alternately bright and
// dark of `amplitude` (file units, decaying over 60 mm) from two molars' and an incisor's fillings behind the lips, the
// dark band a scanner draws between the two molars, and the fillings themselves.
void add_metal_streaks(CtVolume& ct, const Eigen::Vector3d& stomion, double amplitude) {
  const GridGeometry& g = ct.intensity.geometry;
  const std::array<Eigen::Vector2d, 3> metals = {stomion.head<2>() + Eigen::Vector2d(-22, -33),
                                                 stomion.head<2>() + Eigen::Vector2d(22, -33),
                                                 stomion.head<2>() + Eigen::Vector2d(0, -12)};
  const std::array<double, 3> phases = {0.3, 1.7, 2.9};
  const Eigen::Vector2d band = metals[1] - metals[0];
  for (int k = 0; k < g.dims[2]; ++k) {
    const double dz = g.point(0, 0, k).z() - stomion.z();
    if (std::abs(dz) > 8) continue;
    const double taper = 0.5 * (1 + std::cos(M_PI * dz / 8));
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const Eigen::Vector2d p = g.point(i, j, k).head<2>();
        double add = 0;
        for (int m = 0; m < 3; ++m) {
          const Eigen::Vector2d d = p - metals[m];
          const double c = std::cos(9 * std::atan2(d.y(), d.x()) + phases[m]);
          add += amplitude * (c < 0 ? -1 : 1) * std::pow(c, 4) * std::exp(-d.norm() / 60);
          if (d.norm() < 2.5) add += 3000;
        }
        const double t = std::clamp((p - metals[0]).dot(band) / band.squaredNorm(), 0.0, 1.0);
        add -= amplitude * std::exp(-std::pow((p - metals[0] - t * band).norm() / 3, 2));
        ct.intensity(i, j, k) += static_cast<float>(taper * add);
      }
  }
}

TEST(SoftTissue, DentalMetalStreaksAcrossTheMouthLeaveTheModelAndItsLandmarks) {
  // The bundled CT with streaks of 800 file units (about Hounsfield units) from fillings behind its lips: rays brighter
  // than the skin in the air in front of the lips, darker than it across the lips. The same cuts and anatomy, and the
  // landmarks within a few millimetres of the CT's without them, the mouth's the farthest.
  SegmentOptions options;
  options.tets.target_edge_length = 4.0;  // the anatomy does not depend on it; TetGen is quicker
  const CtVolume quiet = read_ct_volume(default_ct());
  const PatientModel reference = build_patient_model(quiet, options);
  CtVolume streaked = quiet;
  add_metal_streaks(streaked, Eigen::Vector3d(97.6, 158.0, 37.5), 800);  // at the stomion read in the CT
  const PatientModel m = build_patient_model(streaked, options);
  expect_valid_patient(m);
  EXPECT_NEAR(m.cuts.top_z, reference.cuts.top_z, 2.0);
  EXPECT_NEAR(m.cuts.bottom_z, reference.cuts.bottom_z, 2.0);
  EXPECT_NEAR(m.cuts.posterior_y, reference.cuts.posterior_y, 2.0);
  const auto landmarks = [](const PatientModel& model) {
    return find_face_landmarks(model.mesh.V, side_mask_of(model.mesh), landmark_options_for(model.mesh, "model"))
        .points;
  };
  const auto before = landmarks(reference), after = landmarks(m);
  double sum = 0;
  for (const auto& [name, point] : before) {
    ASSERT_TRUE(after.count(name)) << name;
    const double apart = (after.at(name) - point).norm();
    EXPECT_LT(apart, 5.0) << name;
    sum += apart;
  }
  EXPECT_LT(sum / before.size(), 1.5);
}

// The mouth of an upright CT opened by `gap` mm at the stomion's depth, as a jaw opens about its joints: below the
// mouth line (a parabola in x through the stomion and the mouth corners' height) everything moves down by the gap
// times how far forward of the tragi's y it lies (a fraction, 1 at the stomion); the band this stretches repeats the
// mouth line's slice, and between the corners (an ellipse as tall as the gap) it is air to 14 mm behind the stomion,
// but for bone (teeth).
void open_mouth(CtVolume& ct, const Eigen::Vector3d& stomion, const Eigen::Vector3d& right, const Eigen::Vector3d& left,
                double tragus_y, double gap, double air, double bone) {
  const Field closed = ct.intensity;
  const GridGeometry& g = closed.geometry;
  const double centre = 0.5 * (right.x() + left.x()), half_width = 0.5 * (left.x() - right.x());
  const double corner_z = 0.5 * (right.z() + left.z());
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const Eigen::Vector3d p = g.point(i, j, k);
        const double u = (p.x() - centre) / half_width;
        const double cut = stomion.z() + (corner_z - stomion.z()) * std::min(1.0, u * u);
        const double drop = gap * std::clamp((p.y() - tragus_y) / (stomion.y() - tragus_y), 0.0, 1.0);
        const double from = p.z() >= cut ? p.z() : p.z() < cut - drop ? p.z() + drop : cut;
        const double t = std::clamp((from - g.origin.z()) / g.spacing.z(), 0.0, g.dims[2] - 1.0);
        const int k0 = std::min(static_cast<int>(t), g.dims[2] - 2);
        float v = static_cast<float>((1 - (t - k0)) * closed(i, j, k0) + (t - k0) * closed(i, j, k0 + 1));
        const double w = (p.z() - (cut - drop / 2)) / std::max(drop / 2, 1e-6);
        if (drop > 0.5 && u * u + w * w < 1 && p.y() > stomion.y() - 14 && v < bone) v = static_cast<float>(air);
        ct.intensity(i, j, k) = v;
      }
}

TEST(SoftTissue, AnOpenMouthIsClosedAcrossTheLipsAndItsLandmarksReadThere) {
  // The bundled CT with its mouth opened 10 mm: segmented as it is, the lips' gap (wider than the cavity closing
  // closes) would leave a pocket 14 mm deep in the skin, whose back the profile takes for the stomion and which the
  // standard's closed mouth cannot follow. The segmentation measures the gap, closes it with a wider closing and says
  // so; the stomion then lies across the lips, and the mouth corners where the closed CT's are.
  SegmentOptions options;
  options.tets.target_edge_length = 4.0;  // the anatomy does not depend on it; TetGen is quicker
  const CtVolume closed = read_ct_volume(default_ct());
  const PatientModel reference = build_patient_model(closed, options);
  EXPECT_EQ(reference.parted_lips, 0);
  EXPECT_EQ(reference.repair.find("open mouth"), std::string::npos) << reference.repair;
  CtVolume opened = closed;
  // At the stomion and mouth corners read in the closed CT, the tragi's y; air and bone in its file units.
  open_mouth(opened, Eigen::Vector3d(97.6, 158.0, 37.5), Eigen::Vector3d(71.0, 156.5, 42.65),
             Eigen::Vector3d(119.2, 159.2, 42.0), 91.2, 10.0, 0.0, 1169.0);
  const PatientModel m = build_patient_model(opened, options);
  expect_valid_patient(m);
  // The gap where the rays pass the lips by more than a closed slit's depth: the opening within a voxel or two.
  EXPECT_GT(m.parted_lips, 2 * options.cavity_closing_radius);
  EXPECT_LT(m.parted_lips, 12.0);
  EXPECT_NE(m.repair.find("open mouth"), std::string::npos) << m.repair;
  std::ostringstream radius;
  radius << "--cavity-closing " << m.options.cavity_closing_radius << ",";
  EXPECT_NE(m.repair.find(radius.str()), std::string::npos) << m.repair;
  EXPECT_GE(m.options.cavity_closing_radius, m.parted_lips / 2 + 1);
  const auto landmarks = [](const PatientModel& model) {
    return find_face_landmarks(model.mesh.V, side_mask_of(model.mesh), landmark_options_for(model.mesh, "model"))
        .points;
  };
  const auto before = landmarks(reference), after = landmarks(m);
  for (const char* name : {"stomion", "cheilion right", "cheilion left", "subnasale", "labrale superius"})
    ASSERT_TRUE(after.count(name)) << name;
  // Across the lips rather than at the pocket's back, 14 mm behind them.
  EXPECT_GT(after.at("stomion").y(), before.at("stomion").y() - 6);
  for (const char* name : {"cheilion right", "cheilion left"}) {
    EXPECT_NEAR(after.at(name).x(), before.at(name).x(), 3.0) << name;
    EXPECT_NEAR(after.at(name).z(), before.at(name).z(), 3.0) << name;
  }
  for (const char* name : {"subnasale", "labrale superius"})
    EXPECT_LT((after.at(name) - before.at(name)).norm(), 2.0) << name;
}

TEST(SoftTissue, AnOpenMouthsClosingIsHalfItsGapAndAMillimetreUpToTheMostItIsRaisedTo) {
  EXPECT_EQ(open_mouth_closing(0, 4), 0);     // lips that meet
  EXPECT_EQ(open_mouth_closing(7.9, 4), 0);   // the default closing bridges them
  EXPECT_EQ(open_mouth_closing(17.0, 9), 0);  // as does a radius the user gave
  EXPECT_EQ(open_mouth_closing(8.0, 4), 5.0);
  EXPECT_EQ(open_mouth_closing(11.5, 4), 7.0);
  EXPECT_EQ(open_mouth_closing(18.0, 4), kMostMouthClosing);
  try {
    open_mouth_closing(18.5, 4);
    ADD_FAILURE() << "lips 18.5 mm apart: no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("the lips are 18.5 mm apart"), std::string::npos) << message;
    EXPECT_NE(message.find("--cavity-closing 10.5"), std::string::npos) << message;
  }
}

TEST(SoftTissue, TheJawCutDoesNotJumpWhenThePosteriorCutFallsBetweenRows) {
  // The bundled CT's working grid has its rows on whole millimetres. A posterior cut on a row and one half a row in
  // front of it meet the same tissue under the chin: the jaw cut, read from the model's rows at the cut near the
  // mid-plane, stays where it is (the radial test near the face's axis looks sideways whatever the half row).
  const CtVolume ct = read_ct_volume(default_ct());
  double jaw[2];
  for (int half = 0; half < 2; ++half) {
    SegmentOptions options;
    options.cuts.posterior_y = 100.0 + 0.5 * half;
    const PatientModel m = build_patient_model(ct, options);
    jaw[half] = m.cuts.jaw_z;
    expect_valid_patient(m);
  }
  EXPECT_GT(jaw[0], 15.0);  // the bottom cut is at z 3: a jaw cut well above it
  EXPECT_NEAR(jaw[1], jaw[0], 1.5);
}

TEST(SoftTissue, AHeadTurnedInTheScannerIsSegmentedInItsHeadFrame) {
  // The bundled CT turned about the vertical by a known angle: the turn is found, the anatomy and the cuts are the
  // upright CT's turned with it (within 3 mm, the clipped nose's plateau 4), the model overlays the turned CT, and its
  // plane is turned so.
  SegmentOptions options;
  options.tets.target_edge_length = 4.0;  // the anatomy does not depend on it; TetGen is quicker
  const CtVolume ct = read_ct_volume(default_ct());
  const PatientModel upright = build_patient_model(ct, options);
  ASSERT_EQ(upright.cuts.turn.degrees, 0);  // this head is upright
  const FaceAnatomy& a = *upright.cuts.anatomy;
  for (const double degrees : {-14.0, 9.0}) {
    HeadTurn scan;  // from the upright CT to the turned one: its face looks towards (sin, cos) of `degrees`
    scan.degrees = -degrees;
    scan.axis = Eigen::Vector2d(100, 100);
    CtVolume turned = ct;
    turned.intensity = turned_to_head_frame(ct.intensity, scan, 1.5,
                                            *std::min_element(ct.intensity.data.begin(), ct.intensity.data.end()));
    const PatientModel m = build_patient_model(turned, options);
    expect_valid_patient(m);
    const HeadTurn& found = m.cuts.turn;
    EXPECT_NEAR(found.degrees, degrees, 1.5);
    ASSERT_TRUE(m.cuts.anatomy);
    const FaceAnatomy& b = *m.cuts.anatomy;
    // Upright CT -> turned CT -> its head frame.
    const auto moved = [&](const Eigen::Vector3d& p) { return found.to_head(scan.to_head(p)); };
    EXPECT_LT((moved(a.pronasale) - b.pronasale).norm(), 4.0) << degrees;  // the middle of the nose's clipped front
    EXPECT_LT((moved(a.nasion) - b.nasion).norm(), 3.0) << degrees;
    EXPECT_LT((moved(a.menton) - b.menton).norm(), 3.0) << degrees;
    EXPECT_NEAR(b.pronasale.y() - m.cuts.posterior_y, a.pronasale.y() - upright.cuts.posterior_y, 3.0);
    EXPECT_NEAR(m.cuts.top_z, upright.cuts.top_z, 3.0);
    EXPECT_NEAR(m.cuts.bottom_z, upright.cuts.bottom_z, 3.0);
    // The model lies in the turned CT's frame: its most anterior skin near the turned pronasale.
    const std::optional<MidSagittalPlane> plane = mid_sagittal_plane(m.mesh, "model");
    ASSERT_TRUE(plane);
    EXPECT_NEAR(std::atan(plane->turn) * 180 / M_PI, found.degrees, 1e-9);
    const Eigen::Vector3d tip = scan.to_head(a.pronasale);
    EXPECT_NEAR(plane->x_at(tip.y(), tip.z()), tip.x(), 3.0);
    double nearest = std::numeric_limits<double>::infinity();
    for (int v = 0; v < m.mesh.num_vertices(); ++v)
      nearest = std::min(nearest, (m.mesh.V.row(v).transpose() - tip).norm());
    EXPECT_LT(nearest, 3.0) << degrees;
  }
}

TEST(SoftTissue, AHeadPitchedInTheScannerIsSegmentedInItsHeadFrameWhenThePitchIsGiven) {
  // The bundled CT pitched about the lateral axis (chin raised by 12 degrees, lowered by 8, onto a grid that holds the
  // whole pitched volume) and segmented with that pitch given: the anatomy and the cuts are the upright CT's moved
  // with it (within 3 mm; the clipped nose's plateau and the ears' front within 6 and 5), the model overlays the
  // pitched CT, and its plane carries the pitch. Without the pitch, the nose is found elsewhere.
  SegmentOptions options;
  options.tets.target_edge_length = 4.0;
  const CtVolume ct = read_ct_volume(default_ct());
  const PatientModel upright = build_patient_model(ct, options);
  const FaceAnatomy& a = *upright.cuts.anatomy;
  for (const double pitch : {12.0, -8.0}) {
    HeadTurn scan;  // from the upright CT to the pitched one
    scan.pitch = -pitch;
    scan.axis = Eigen::Vector2d(100, 100);
    scan.axis_z = 70;
    CtVolume pitched = ct;
    pitched.intensity = turned_to_head_frame(ct.intensity, scan, 1.5,
                                             *std::min_element(ct.intensity.data.begin(), ct.intensity.data.end()));
    SegmentOptions given = options;
    given.cuts.head_pitch = pitch;
    const PatientModel m = build_patient_model(pitched, given);
    expect_valid_patient(m);
    const HeadTurn& found = m.cuts.turn;
    EXPECT_EQ(found.pitch, pitch);
    EXPECT_EQ(found.degrees, 0);  // a pitch is no turn: the head's mirror symmetry is the same
    const FaceAnatomy& b = *m.cuts.anatomy;
    const auto moved = [&](const Eigen::Vector3d& p) { return found.to_head(scan.to_head(p)); };
    // The head frames of the upright and the pitched CT differ by a shift (their axes are not the same line).
    const Eigen::Vector3d shift = moved(Eigen::Vector3d::Zero());
    // The clipped nose's front: its middle in height moves with how the resampling blurs the cut's ends.
    EXPECT_LT(std::abs(moved(a.pronasale).y() - b.pronasale.y()), 3.0) << pitch;
    EXPECT_LT((moved(a.pronasale) - b.pronasale).norm(), 6.0) << pitch;
    EXPECT_LT((moved(a.nasion) - b.nasion).norm(), 3.0) << pitch;
    EXPECT_LT((moved(a.menton) - b.menton).norm(), 3.0) << pitch;
    EXPECT_NEAR(m.cuts.top_z, upright.cuts.top_z + shift.z(), 3.0) << pitch;
    EXPECT_NEAR(m.cuts.bottom_z, upright.cuts.bottom_z + shift.z(), 3.0) << pitch;
    // The ears' front (rule 5, core/segment/face_anatomy.h) moves by a few millimetres with the resampling's blur, as
    // with a turn found a tenth of a degree differently (docs/benchmarks.md).
    EXPECT_NEAR(m.cuts.posterior_y, upright.cuts.posterior_y + shift.y(), 5.0) << pitch;
    const std::optional<MidSagittalPlane> plane = mid_sagittal_plane(m.mesh, "model");
    ASSERT_TRUE(plane);
    EXPECT_EQ(plane->pitch, pitch);
    // The hard palate, read in the head frame, slopes in the CT's frame as the upright's pitched.
    ASSERT_TRUE(upright.cuts.palate_pitch && m.cuts.palate_pitch);
    EXPECT_NEAR(*m.cuts.palate_pitch, *upright.cuts.palate_pitch + pitch, 2.0) << pitch;
    const Eigen::Vector3d tip = scan.to_head(a.pronasale);
    double nearest = std::numeric_limits<double>::infinity();
    for (int v = 0; v < m.mesh.num_vertices(); ++v)
      nearest = std::min(nearest, (m.mesh.V.row(v).transpose() - tip).norm());
    EXPECT_LT(nearest, 3.0) << pitch;
    // In the scan's own frame the same CT gives another face region.
    if (pitch == 12.0) {
      try {
        const PatientModel unpitched = build_patient_model(pitched, options);
        const FaceAnatomy& c = *unpitched.cuts.anatomy;
        // the clipped nose's front is read where the tilted field-of-view cut leaves it
        EXPECT_GT((scan.to_head(a.pronasale) - c.pronasale).norm(), 10.0);
      } catch (const Error&) {
        // refused: as wrong for the user as a wrong region, and said
      }
    }
  }
}

TEST(SoftTissue, ALargeModelIsMeshedCoarserUnlessTheEdgeLengthIsGiven) {
  const CtVolume ct = testing::ellipsoid_phantom();
  SegmentOptions o = testing::phantom_options(ct);
  o.coarsen_above_tets = 0;
  const PatientModel given = build_patient_model(ct, o);
  EXPECT_EQ(given.edge_length, 3.0);
  // A goal of an eighth of the tets at 3 mm: about twice the edge length, and far fewer tets.
  o.coarsen_above_tets = given.mesh.num_cells() / 8.0;
  const PatientModel coarse = build_patient_model(ct, o);
  EXPECT_GT(coarse.edge_length, 1.6 * 3.0);
  EXPECT_LT(coarse.edge_length, 2.4 * 3.0);
  EXPECT_LT(coarse.mesh.num_cells(), given.mesh.num_cells() / 4);
  expect_valid_patient(coarse);
  // A goal the model is below already leaves the edge length as given.
  o.coarsen_above_tets = 10.0 * given.mesh.num_cells();
  EXPECT_EQ(build_patient_model(ct, o).edge_length, 3.0);
}

TEST(SoftTissue, ACoarseScanIsMeshedAtItsVoxelSpacingUnlessTheEdgeLengthIsGiven) {
  const CtVolume ct = testing::ellipsoid_phantom(3.5);
  SegmentOptions o = testing::phantom_options(ct);
  o.coarsen_above_tets = 0;
  const PatientModel coarse = build_patient_model(ct, o);
  EXPECT_EQ(coarse.edge_length, 3.5);
  EXPECT_EQ(coarse.edge_length_rule, "the CT's coarsest voxel spacing");
  expect_valid_patient(coarse);
  o.follow_scan_spacing = false;
  const PatientModel given = build_patient_model(ct, o);
  EXPECT_EQ(given.edge_length, 3.0);
  EXPECT_EQ(given.edge_length_rule, "");
  EXPECT_GT(given.mesh.num_cells(), coarse.mesh.num_cells());
  // The coarsest axis counts; a longer target wins; the scan sets at most kMostScanEdgeLength.
  EXPECT_EQ(scan_edge_length(Eigen::Vector3d(0.5, 0.5, 0.6), 2.0), 2.0);
  EXPECT_EQ(scan_edge_length(Eigen::Vector3d(0.5, 0.5, 3.0), 2.0), 3.0);
  EXPECT_EQ(scan_edge_length(Eigen::Vector3d(1.0, 1.0, 1.0), 4.5), 4.5);
  EXPECT_EQ(scan_edge_length(Eigen::Vector3d(5.0, 5.0, 7.0), 2.0), kMostScanEdgeLength);
}

void expect_error(const std::function<void()>& run, const std::string& subject, const std::string& words) {
  try {
    run();
    FAIL() << "expected facehex::Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.subject(), subject) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(SoftTissue, ReportsItsStepsAndCanBeCancelled) {
  const CtVolume ct = testing::ellipsoid_phantom();
  std::vector<std::string> stages;
  // Cancelled when the surface is due: nothing after it runs.
  const ProgressCallback cancel_at_surface = [&stages](const std::string& stage, double) {
    stages.push_back(stage);
    return stage != "segmentation: the surface";
  };
  EXPECT_THROW(build_patient_model(ct, testing::phantom_options(ct), cancel_at_surface), Cancelled);
  ASSERT_GE(stages.size(), 3u);
  EXPECT_EQ(stages.front(), "segmentation: the CT's noise");  // measured first: a noisy CT is blurred before the rest
  EXPECT_EQ(stages.back(), "segmentation: the surface");
}

TEST(SoftTissue, RejectsThresholdsInTheWrongOrder) {
  const CtVolume ct = testing::ellipsoid_phantom();
  SegmentOptions o = testing::phantom_options(ct);
  o.skin_threshold = 1500;
  o.bone_threshold = 500;
  expect_error([&] { build_patient_model(ct, o); }, "thresholds", "must be below");
}

TEST(SoftTissue, RejectsAVolumeWithoutSkin) {
  CtVolume ct = testing::ellipsoid_phantom();
  for (float& v : ct.intensity.data) v = std::min(v, 100.0f);  // air only
  SegmentOptions o = testing::phantom_options(ct);
  o.skin_threshold = 500;
  o.bone_threshold = 1150;
  expect_error([&] { build_patient_model(ct, o); }, "segment", "skin threshold");
}

// Volumes that are no head are refused with that word when the cuts are to be found in them: a tall box of soft
// tissue around a bone core (a phantom), a CT of 8 x 8 x 8 voxels, and a head whose bone threshold no voxel reaches.
TEST(SoftTissue, RefusesWhatIsNotAPlausibleHead) {
  CtVolume box;
  box.source = "box";
  GridGeometry& g = box.intensity.geometry;
  g.dims = {70, 80, 130};
  g.spacing = Eigen::Vector3d::Constant(2.0);
  box.intensity.data.assign(g.size(), 0.0f);
  for (int k = 5; k < 125; ++k)
    for (int j = 5; j < 75; ++j)
      for (int i = 5; i < 65; ++i)
        box.intensity(i, j, k) = (i >= 25 && i < 45 && j >= 25 && j < 55) ? 2000.0f : 1000.0f;
  SegmentOptions o;
  o.working_spacing = 2.0;
  expect_error([&] { build_patient_model(box, o); }, "segment", "not a plausible head: no nose stands out");

  CtVolume tiny;
  tiny.intensity.geometry.dims = {8, 8, 8};
  tiny.intensity.data.assign(512, 0.0f);
  for (int k = 2; k < 6; ++k)
    for (int j = 2; j < 6; ++j)
      for (int i = 2; i < 6; ++i) tiny.intensity(i, j, k) = (i == 3 && j == 3) ? 2000.0f : 1000.0f;
  expect_error([&] { build_patient_model(tiny, o); }, "segment", "not a plausible head: the body found is");

  SegmentOptions no_bone;
  no_bone.bone_threshold = std::numeric_limits<double>::infinity();
  expect_error([&] { build_patient_model(read_ct_volume(default_ct()), no_bone); }, "segment",
               "not a plausible head: no voxel of the head reaches the bone threshold");
}

// The bundled CT as a scan cropped to the voxels lo <= (i, j, k) < hi would hold it.
CtVolume cropped_bundled_ct(const std::array<int, 3>& lo, const std::array<int, 3>& hi) {
  CtVolume ct = read_ct_volume(default_ct());
  ct.intensity = crop(ct.intensity, lo, hi);
  return ct;
}

TEST(SoftTissue, AScanThatEndsBehindTheFaceIsCutWhereItEnds) {
  // The bundled CT as if its field of view ended at y 96 mm, behind its posterior cut (y 100.2) but in front of its
  // ears (auricles' front 88, tragi 91): the ears are not in the scan, and the posterior cut is placed border_margin in
  // front of where the scan ends rather than where the ear rules would put it in the rows left.
  const CtVolume ct = read_ct_volume(default_ct());
  const PatientModel whole = build_patient_model(ct);
  const int j0 = 30;               // y = 96 mm
  SegmentOptions same_thresholds;  // the crop's histogram has less air
  same_thresholds.skin_threshold = whole.thresholds.skin;
  same_thresholds.bone_threshold = whole.thresholds.bone;
  const PatientModel cut = build_patient_model(cropped_bundled_ct({0, j0, 0}, {64, 64, 93}), same_thresholds);
  expect_valid_patient(cut);
  EXPECT_FALSE(cut.cuts.turn.turned()) << cut.cuts.turn.degrees;
  ASSERT_TRUE(cut.cuts.scan_edge_y);
  EXPECT_NEAR(*cut.cuts.scan_edge_y, j0 * 3.2, 1e-3);
  EXPECT_FALSE(cut.cuts.scan_edge_at_disc);
  EXPECT_TRUE(cut.cuts.posterior_at_scan_edge);
  // The surface moves a cut by a fraction of a voxel where it would fall on a voxel plane (level_surface_with_cuts).
  EXPECT_NEAR(cut.cuts.posterior_y, j0 * 3.2 + FaceCutOptions{}.border_margin, 0.5);
  EXPECT_FALSE(cut.cuts.anatomy->tragi[0] || cut.cuts.anatomy->tragi[1]);
  // The face in front is the same: the other cuts, and the model's front. The mid-sagittal plane moves by less than
  // half this CT's 3.2 mm voxel: its levels' symmetry, on the face's front, loses the back of the head's sections.
  EXPECT_FALSE(whole.cuts.posterior_at_scan_edge);
  EXPECT_NEAR(cut.cuts.top_z, whole.cuts.top_z, 0.5);
  EXPECT_NEAR(cut.cuts.bottom_z, whole.cuts.bottom_z, 0.5);
  EXPECT_NEAR(cut.cuts.centre_x, whole.cuts.centre_x, 1.6);
  // Its symmetry fit leans by several degrees with half the levels behind it; the landmarks are read upright.
  EXPECT_EQ(landmark_plane(cut.cuts, same_thresholds.cuts).slope, 0.0);
  EXPECT_NEAR(cut.mesh.V.col(1).maxCoeff(), whole.mesh.V.col(1).maxCoeff(), 1.0);
  EXPECT_GE(cut.mesh.V.col(1).minCoeff(), cut.cuts.posterior_y - 1e-4);
}

// The bundled CT as a scanner would have reconstructed it in a disc about `centre` (x, y mm): the columns beyond
// `radius` hold the CT's lowest value in every slice.
CtVolume bundled_ct_in_disc(const Eigen::Vector2d& centre, double radius) {
  CtVolume ct = read_ct_volume(default_ct());
  const GridGeometry& g = ct.intensity.geometry;
  const float lowest = *std::min_element(ct.intensity.data.begin(), ct.intensity.data.end());
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i)
        if ((g.point(i, j, k).head<2>() - centre).norm() > radius) ct.intensity(i, j, k) = lowest;
  return ct;
}

TEST(SoftTissue, AScanReconstructedInADiscNarrowerThanTheHeadIsCutInFrontOfWhereItEnds) {
  // A disc of radius 82 mm about (97.6, 145): the nose tip (y 184) lies inside it, the sides of the head behind the
  // face outside it, and the ears (tragi at y 91) beyond it. The scan ends across the head on the disc's edge, inside
  // the volume's box: the posterior cut is placed in front of that, as where a box ends across the head.
  const CtVolume ct = read_ct_volume(default_ct());
  const PatientModel whole = build_patient_model(ct);
  SegmentOptions same_thresholds;  // the fill changes the histogram's air
  same_thresholds.skin_threshold = whole.thresholds.skin;
  same_thresholds.bone_threshold = whole.thresholds.bone;
  const Eigen::Vector2d centre(97.6, 145);
  constexpr double radius = 82;
  const PatientModel cut = build_patient_model(bundled_ct_in_disc(centre, radius), same_thresholds);
  expect_valid_patient(cut);
  ASSERT_TRUE(cut.cuts.scan_edge_y);
  EXPECT_TRUE(cut.cuts.posterior_at_scan_edge);
  EXPECT_TRUE(cut.cuts.scan_edge_at_disc);
  EXPECT_GT(*cut.cuts.scan_edge_y, whole.cuts.posterior_y);
  EXPECT_LT(*cut.cuts.scan_edge_y, centre.y());
  EXPECT_NEAR(cut.cuts.posterior_y, *cut.cuts.scan_edge_y + FaceCutOptions{}.border_margin, 0.5);
  EXPECT_GE(cut.mesh.V.col(1).minCoeff(), cut.cuts.posterior_y - 1e-4);
  // Everything meshed lies in the disc, and the face in front is the same.
  for (int v = 0; v < cut.mesh.V.rows(); ++v)
    ASSERT_LE((cut.mesh.V.row(v).head<2>().transpose() - centre).norm(), radius + 1e-6) << v;
  EXPECT_NEAR(cut.cuts.top_z, whole.cuts.top_z, 0.5);
  EXPECT_NEAR(cut.cuts.bottom_z, whole.cuts.bottom_z, 0.5);
  EXPECT_NEAR(cut.mesh.V.col(1).maxCoeff(), whole.mesh.V.col(1).maxCoeff(), 1.0);
}

TEST(SoftTissue, AScanThatEndsBehindTheEarsKeepsTheEarsCut) {
  // The bundled CT cropped at y 38.4 mm, across the back of the head well behind the ears: the ears are in the scan
  // and place the posterior cut, as on the whole scan.
  const CtVolume ct = read_ct_volume(default_ct());
  const PatientModel whole = build_patient_model(ct);
  SegmentOptions same_thresholds;
  same_thresholds.skin_threshold = whole.thresholds.skin;
  same_thresholds.bone_threshold = whole.thresholds.bone;
  const PatientModel cut = build_patient_model(cropped_bundled_ct({0, 12, 0}, {64, 64, 93}), same_thresholds);
  ASSERT_TRUE(cut.cuts.scan_edge_y);
  EXPECT_LT(*cut.cuts.scan_edge_y, 60);
  EXPECT_FALSE(cut.cuts.posterior_at_scan_edge);
  EXPECT_NEAR(cut.cuts.posterior_y, whole.cuts.posterior_y, 0.5);
}

TEST(SoftTissue, AScanThatEndsAcrossTheCheeksIsRefusedNamingThePosteriorCut) {
  // The bundled CT cropped to x 41.6-160 mm: the scan ends across the cheeks, a few centimetres behind the nose.
  expect_error(
      [&] {
        build_patient_model(cropped_bundled_ct({13, 0, 0}, {51, 64, 93}));
      },
      "segment", "the scan ends across the head");
  expect_error(
      [&] {
        build_patient_model(cropped_bundled_ct({13, 0, 0}, {51, 64, 93}));
      },
      "segment", "--posterior-cut");
  // Given a posterior cut, the user's choice is meshed.
  SegmentOptions given;
  given.cuts.posterior_y = 150;
  const PatientModel m = build_patient_model(cropped_bundled_ct({13, 0, 0}, {51, 64, 93}), given);
  EXPECT_EQ(m.cuts.posterior_y, 150);
  EXPECT_GT(m.mesh.num_cells(), 1000);
}

}  // namespace
}  // namespace facehex
