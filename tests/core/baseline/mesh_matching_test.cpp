// The mesh-matching baseline: its thin-plate spline, and the registration of a box onto an affine image of it.
#include "core/baseline/mesh_matching.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "core/baseline/thin_plate_spline.h"
#include "core/mesh/hex_to_tets.h"
#include "core/mesh/tet_topology.h"
#include "core/quality/surface_distance.h"
#include "core/util/error.h"
#include "tests/core/test_meshes.h"

namespace facehex {
namespace {

Eigen::MatrixXd random_points(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-10, 10);
  Eigen::MatrixXd X(n, 3);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) X(i, k) = d(rng);
  return X;
}

// x -> M x + t with a rotation, an anisotropic scale and a shear: the patient frame of the tests.
Eigen::Matrix3d test_matrix() {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.15, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Eigen::Matrix3d S;
  S << 1.3, 0.2, 0.0,  //
      0.0, 0.9, 0.1,   //
      0.0, 0.0, 1.1;
  return 2.5 * R * S;
}
const Eigen::RowVector3d kShift(120, -40, 310);

Eigen::MatrixXd affine(const Eigen::MatrixXd& X) { return (X * test_matrix().transpose()).rowwise() + kShift; }

TEST(ThinPlateSpline, ReproducesAffineMapsAtAnyStiffness) {
  const Eigen::MatrixXd C = random_points(30, 1), P = random_points(200, 2), X = random_points(50, 3);
  const Eigen::VectorXd w = Eigen::VectorXd::Constant(P.rows(), 1.0 / P.rows());
  for (const double stiffness : {0.0, 1e-3, 10.0}) {
    ThinPlateSpline spline(C);
    spline.fit(P, affine(P), w, stiffness);
    EXPECT_LT((spline(X) - affine(X)).cwiseAbs().maxCoeff(), 1e-8) << "stiffness " << stiffness;
  }
}

TEST(ThinPlateSpline, FollowsTheControlsWhenSoftAndStaysAffineWhenStiff) {
  const Eigen::MatrixXd C = random_points(40, 4);
  Eigen::MatrixXd Q = C;
  Q.col(1) += (C.col(0) * 0.3).array().sin().matrix() * 2.0;  // a bend no affine map reproduces
  const Eigen::VectorXd w = Eigen::VectorXd::Constant(C.rows(), 1.0 / C.rows());
  ThinPlateSpline soft(C), stiff(C);
  soft.fit(C, Q, w, 1e-9);
  stiff.fit(C, Q, w, 1e6);
  EXPECT_LT((soft(C) - Q).cwiseAbs().maxCoeff(), 1e-4);  // (nearly) interpolates its own controls
  // The stiff fit is the least-squares affine map: its residual is orthogonal to [C 1].
  Eigen::MatrixXd H(C.rows(), 4);
  H << C, Eigen::VectorXd::Ones(C.rows());
  const Eigen::MatrixXd best_affine = H * H.colPivHouseholderQr().solve(Q);
  EXPECT_LT((stiff(C) - best_affine).cwiseAbs().maxCoeff(), 1e-3);
}

// The standard: a face-like slab of hexes (+x lateral, +y towards the skin, +z up); the patient: a finer tet mesh of
// the same box in another frame (rotated, sheared, scaled, far away), with its own side labels.
struct BoxCase {
  VolumeMesh standard, patient;
};

BoxCase box_case() {
  BoxCase b;
  b.standard = test::hex_box(6, 3, 8, 60, 15, 80);
  const VolumeMesh fine = test::hex_box(10, 4, 12, 60, 15, 80);
  b.patient = VolumeMesh::from_tets(affine(fine.V), split_into_tets(fine).T);
  b.patient.point_data = fine.point_data;
  return b;
}

TEST(MeshMatching, MapsABoxOntoAnAffineImageOfItNearlyExactly) {
  const BoxCase b = box_case();
  const MeshMatchingResult r = mesh_matching(b.standard, "standard box", b.patient, "patient box");
  ASSERT_EQ(r.hex.num_vertices(), b.standard.num_vertices());
  EXPECT_EQ(r.hex.C, b.standard.C);
  // Every node, inside too, lands where the affine map sends it (the box is 80 x 2.5 = 200 mm tall there).
  const double error = (r.hex.V - affine(b.standard.V)).rowwise().norm().maxCoeff();
  EXPECT_LT(error, 0.2) << "mm";
  // Boundary vertices (those on a side) lie on the patient's surface.
  std::vector<int> boundary;
  for (int v = 0; v < b.standard.num_vertices(); ++v)
    if (b.standard.point_data.at(kSideMaskArray)(v) != 0) boundary.push_back(v);
  const Eigen::MatrixXd mapped_boundary = r.hex.V(boundary, Eigen::all);
  const Eigen::MatrixXi F = boundary_faces(b.patient.tets()).F;
  EXPECT_LT(distances_to_surface(mapped_boundary, b.patient.V, F).maxCoeff(), 0.05) << "mm";
  EXPECT_NEAR(r.scale, std::cbrt(test_matrix().determinant()), 0.3);
  // The iterations converge: the last pairs are much closer than the first.
  ASSERT_FALSE(r.iterations.empty());
  EXPECT_LT(r.iterations.back().standard_to_patient_mm, 0.01 * r.iterations.front().standard_to_patient_mm);
  for (const char* stage : {"surfaces", "similarity", "spline", "apply"}) EXPECT_EQ(r.seconds.count(stage), 1u);
}

TEST(ThinPlateSpline, SingularFitIsAnError) {
  Eigen::MatrixXd P = random_points(20, 5);
  P.col(2).setZero();  // all pairs on one plane: the affine part is undetermined without stiffness
  const Eigen::VectorXd w = Eigen::VectorXd::Constant(P.rows(), 1.0 / P.rows());
  ThinPlateSpline spline(random_points(10, 6));
  EXPECT_THROW(spline.fit(P, P, w, 0.0), Error);
}

// Landmark pairs that agree with the surfaces change nothing; pairs that disagree pull the map towards them, and the
// snap (the default) carries the standard's landmark exactly onto the patient's; pairs of unequal lengths are refused.
TEST(MeshMatching, LandmarkPairsPullTheRegistrationAndSnapOntoThePatients) {
  const BoxCase b = box_case();
  PointPairs pairs;
  pairs.standard.resize(2, 3);
  pairs.standard << 30, 15, 40,  //
      30, 15, 70;
  pairs.patient = affine(pairs.standard);
  const MeshMatchingResult agreeing =
      mesh_matching(b.standard, "standard box", b.patient, "patient box", {}, {}, &pairs);
  EXPECT_LT((agreeing.hex.V - affine(b.standard.V)).rowwise().norm().maxCoeff(), 0.2) << "mm";
  // The patient's landmarks 6 mm (before the 2.5x frame scale) to the side: without the snap, the standard's skin
  // point at the landmark follows, where without the pairs it stays.
  PointPairs sideways = pairs;
  sideways.patient = affine(pairs.standard.rowwise() + Eigen::RowVector3d(6, 0, 0));
  sideways.weight = 0.5;
  sideways.snap_radius = 0;
  const MeshMatchingResult pulled =
      mesh_matching(b.standard, "standard box", b.patient, "patient box", {}, {}, &sideways);
  int at = -1;
  for (int v = 0; v < b.standard.num_vertices(); ++v)
    if ((b.standard.V.row(v) - Eigen::RowVector3d(30, 15, 40)).norm() < 1e-9) at = v;
  ASSERT_GE(at, 0);
  const Eigen::RowVector3d plain = affine(b.standard.V.row(at)), wanted = affine(Eigen::RowVector3d(36, 15, 40));
  const double moved = (pulled.hex.V.row(at) - plain).dot((wanted - plain).normalized());
  EXPECT_GT(moved, 0.3 * (wanted - plain).norm()) << "mm towards the landmark";
  // Snapped: exactly on it; vertices farther than the radius from both registered landmarks as without the snap (up to
  // the spline's round-off from run to run).
  sideways.snap_radius = 25;
  const MeshMatchingResult snapped =
      mesh_matching(b.standard, "standard box", b.patient, "patient box", {}, {}, &sideways);
  EXPECT_LT((snapped.hex.V.row(at) - wanted).norm(), 1e-9);
  int far = 0;
  for (int v = 0; v < b.standard.num_vertices(); ++v) {
    const Eigen::RowVector3d x = pulled.hex.V.row(v);
    if ((x - pulled.hex.V.row(at)).norm() < 30 || (x - affine(Eigen::RowVector3d(30, 15, 70))).norm() < 40) continue;
    EXPECT_LT((snapped.hex.V.row(v) - pulled.hex.V.row(v)).norm(), 1e-5);
    ++far;
  }
  EXPECT_GT(far, 0);
  PointPairs unequal = pairs;
  unequal.patient.conservativeResize(1, 3);
  EXPECT_THROW(mesh_matching(b.standard, "standard box", b.patient, "patient box", {}, {}, &unequal), Error);
}

TEST(MeshMatching, RejectsModelsWithoutSidesOrFacingAway) {
  BoxCase b = box_case();
  VolumeMesh unlabelled = b.patient;
  unlabelled.point_data.clear();
  try {
    mesh_matching(b.standard, "standard box", unlabelled, "patient box");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("patient box: no \"side_mask\""), std::string::npos) << e.what();
  }
  // Skin behind the bone: the face looks to -y.
  VolumeMesh turned = b.patient;
  turned.V.col(1) *= -1;
  turned.V.col(0) *= -1;  // a rotation by 180 degrees about z keeps the tets positive
  try {
    mesh_matching(b.standard, "standard box", turned, "patient box");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("+y"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace facehex
