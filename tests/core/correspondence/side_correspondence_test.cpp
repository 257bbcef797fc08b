// The dense correspondence on a side: the standard's parameters pulled back to the patient's side vertices through
// the registered standard surface (side_correspondence.h), and the whole registration on a box (registered_sides.h).
#include "core/correspondence/side_correspondence.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/correspondence/registered_sides.h"
#include "core/fields/constraint_set.h"
#include "core/fields/tet_domain.h"
#include "core/mesh/hex_to_tets.h"
#include "core/quality/surface_distance.h"
#include "core/util/error.h"
#include "tests/core/test_meshes.h"

namespace facehex {
namespace {

// A box of hexes split into tets as a tet domain with its sides (hex_box's: y = sy is the skin, w1).
TetDomain box_domain(int n, double size) { return auxiliary_domain(test::hex_box(n, n, n, size, size, size)); }

// A field that is linear in space on the box: what any interpolation must reproduce exactly.
Eigen::MatrixXd linear_uvw(const Eigen::MatrixXd& V, double size) {
  Eigen::MatrixXd uvw(V.rows(), 3);
  uvw.col(0) = V.col(0) / size;
  uvw.col(1) = 0.3 * V.col(2) / size + 0.2 * V.col(0) / size;
  uvw.col(2) = V.col(1) / size;
  return uvw;
}

TEST(SideTriangles, AreTheBoundaryTrianglesOfOneSide) {
  const TetDomain d = box_domain(3, 30);
  const Eigen::MatrixXi F = side_triangles(d.T, d.side_mask, W1);
  EXPECT_EQ(F.rows(), 2 * 3 * 3);  // each of the 3 x 3 quads of the face y = 30 in two triangles
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(d.V(F(f, k), 1), 30.0);
  EXPECT_EQ(side_triangles(d.T, Eigen::VectorXi::Zero(d.V.rows()), W1).rows(), 0);
}

// The patient is a finer tessellation of the same box; with the identity registration each patient skin vertex gets
// the linear field's value at its own position, exactly; with the standard registered 2 mm along x, the value at a
// point 2 mm back.
TEST(SideCorrespondence, PullsALinearFieldBackExactly) {
  const TetDomain standard = box_domain(3, 30);
  const Eigen::MatrixXd uvw = linear_uvw(standard.V, 30);
  const TetDomain patient = box_domain(7, 30);
  const Eigen::MatrixXi F = side_triangles(standard.T, standard.side_mask, W1);
  const SideCorrespondence same = side_correspondence(standard.V, F, uvw, patient.V, patient.side_mask, W1);
  ASSERT_EQ(same.vertices.size(), 6u * 6u);  // the skin's vertices on no other side: 8 x 8 minus the rim
  for (size_t i = 0; i < same.vertices.size(); ++i) {
    const Eigen::RowVector3d x = patient.V.row(same.vertices[i]);
    EXPECT_NEAR(same.distance(static_cast<Eigen::Index>(i)), 0, 1e-9);
    EXPECT_NEAR(same.uvw(static_cast<Eigen::Index>(i), 0), x(0) / 30, 1e-12);
    EXPECT_NEAR(same.uvw(static_cast<Eigen::Index>(i), 1), 0.3 * x(2) / 30 + 0.2 * x(0) / 30, 1e-12);
  }
  Eigen::MatrixXd shifted = standard.V;
  shifted.col(0).array() += 2.0;
  const SideCorrespondence moved = side_correspondence(shifted, F, uvw, patient.V, patient.side_mask, W1);
  for (size_t i = 0; i < moved.vertices.size(); ++i) {
    const Eigen::RowVector3d x = patient.V.row(moved.vertices[i]);
    // Vertices in front of the shifted surface's edge x = 2 correspond to a point of its rim; no other does.
    EXPECT_EQ(moved.on_rim[i] != 0, x(0) < 2.0) << "x = " << x(0);
    EXPECT_EQ(same.on_rim[i], 0);
    if (x(0) < 2.0) continue;
    EXPECT_NEAR(moved.uvw(static_cast<Eigen::Index>(i), 0), (x(0) - 2.0) / 30, 1e-12);
  }
}

// The whole registration on a box and a stretched copy of it: the skin conditions are the standard's parameters at
// the stretched positions (the registration recovers the stretch), and a model without a skin is named.
TEST(RegisteredSides, FollowAStretchOfTheSameBox) {
  const TetDomain standard = box_domain(4, 40);
  const Eigen::MatrixXd uvw = linear_uvw(standard.V, 40);
  VolumeMesh patient = test::hex_box(6, 6, 6, 40, 40, 40);
  patient.V.col(0) *= 1.15;  // 15 % wider
  const TetDomain patient_tets = auxiliary_domain(patient);
  VolumeMesh patient_model = VolumeMesh::from_tets(patient_tets.V, patient_tets.T);
  patient_model.point_data[kSideMaskArray] = patient_tets.side_mask.cast<double>();
  const RegisteredSidesOptions options;
  const RegisteredSides r = register_sides(standard, uvw, patient_model, "stretched box", options);
  ASSERT_EQ(r.conditions[0].vertices.size(), 5u * 5u);
  EXPECT_EQ(r.vertices_too_far, 0);
  EXPECT_LT(r.distance.max, 0.05);
  for (size_t i = 0; i < r.conditions[0].vertices.size(); ++i) {
    const Eigen::RowVector3d x = patient_tets.V.row(r.conditions[0].vertices[i]);
    EXPECT_NEAR(r.conditions[0].values[i], x(0) / 1.15 / 40, 0.01) << "u at x = " << x(0);
    EXPECT_NEAR(r.conditions[1].values[i], 0.3 * x(2) / 40 + 0.2 * x(0) / 1.15 / 40, 0.01);
  }
  ASSERT_EQ(r.standard_matched.size(), static_cast<size_t>(standard.V.rows()));
  for (Eigen::Index v = 0; v < standard.V.rows(); ++v)
    EXPECT_EQ(r.standard_matched[static_cast<size_t>(v)] != 0, (standard.side_mask(v) & side_bit(W1)) != 0);

  VolumeMesh no_skin = patient_model;
  Eigen::VectorXi without_skin = patient_tets.side_mask;
  for (Eigen::Index v = 0; v < without_skin.size(); ++v) without_skin(v) &= ~side_bit(W1);
  no_skin.point_data[kSideMaskArray] = without_skin.cast<double>();
  EXPECT_THROW(register_sides(standard, uvw, no_skin, "box without skin", options), Error);
}

// A landmark pair snapped onto the patient (PointPairs::snap_radius): the patient's skin triangle under the landmark
// takes values whose interpolation there is the standard's landmark vertex's (u, v), exactly, so that the fields put
// that vertex on the landmark; without the snap no triangle is pinned.
TEST(RegisteredSides, PinTheStandardsLandmarkVertexOntoTheSnappedLandmark) {
  const TetDomain standard = box_domain(4, 40);
  const Eigen::MatrixXd uvw = linear_uvw(standard.V, 40);
  VolumeMesh patient = test::hex_box(6, 6, 6, 40, 40, 40);
  patient.V.col(0) *= 1.15;
  const TetDomain patient_tets = auxiliary_domain(patient);
  VolumeMesh patient_model = VolumeMesh::from_tets(patient_tets.V, patient_tets.T);
  patient_model.point_data[kSideMaskArray] = patient_tets.side_mask.cast<double>();
  Eigen::Index vertex = -1;
  (standard.V.rowwise() - Eigen::RowVector3d(20, 40, 20)).rowwise().squaredNorm().minCoeff(&vertex);
  ASSERT_LT((standard.V.row(vertex) - Eigen::RowVector3d(20, 40, 20)).norm(), 1e-9);
  PointPairs pair;
  pair.standard = standard.V.row(vertex);
  pair.patient.resize(1, 3);
  pair.patient << 1.15 * 20 + 4.1, 40, 23.3;  // on the skin, 4 mm beside where the stretch puts the vertex
  const RegisteredSidesOptions options;
  const RegisteredSides r = register_sides(standard, uvw, patient_model, "stretched box", options, &pair);
  EXPECT_EQ(r.pinned_landmarks, 1);
  const Eigen::MatrixXi skin = side_triangles(patient_tets.T, patient_tets.side_mask, W1);
  const SurfaceLocator::Hits hit = SurfaceLocator(patient_tets.V, skin).closest(pair.patient);
  const Eigen::Vector3i tri = skin.row(hit.face(0)).transpose();
  const Eigen::Vector3d b = triangle_barycentric(pair.patient, patient_tets.V.row(tri(0)), patient_tets.V.row(tri(1)),
                                                 patient_tets.V.row(tri(2)));
  for (int f = 0; f < 2; ++f) {
    double at = 0;
    for (int k = 0; k < 3; ++k) {
      const auto& c = r.conditions[f];
      const auto it = std::find(c.vertices.begin(), c.vertices.end(), tri(k));
      ASSERT_NE(it, c.vertices.end());
      EXPECT_EQ(std::count(c.vertices.begin(), c.vertices.end(), tri(k)), 1);
      at += b(k) * c.values[static_cast<size_t>(it - c.vertices.begin())];
    }
    EXPECT_NEAR(at, uvw(vertex, f), 1e-9) << "field " << f;
  }
  pair.snap_radius = 0;
  EXPECT_EQ(register_sides(standard, uvw, patient_model, "stretched box", options, &pair).pinned_landmarks, 0);
}

}  // namespace
}  // namespace facehex
