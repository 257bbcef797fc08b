#include "core/mesh/corner_jacobian.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "tests/core/test_meshes.h"

namespace facehex {
namespace {

// Right-triangle prism (0,0,0), (0,1,0), (1,0,0) (clockwise from +z, as VTK wants), height 1.
CellNodes right_prism() {
  CellNodes X = CellNodes::Zero();
  X.topRows(6) << 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 1, 1, 1, 0, 1;
  return X;
}

CellNodes mapped(const CellNodes& X, const Eigen::Matrix3d& M) { return X * M.transpose(); }

TEST(CornerJacobian, UnitCubeCornersAreRightHandedUnitFrames) {
  const CellNodes X = ideal_cell(CellType::Hex);
  for (int k = 0; k < 8; ++k) {
    const Eigen::Matrix3d A = corner_jacobian(CellType::Hex, X, k);
    EXPECT_TRUE((A.transpose() * A).isIdentity(0)) << "corner " << k;
    EXPECT_EQ(A.determinant(), 1.0) << "corner " << k;
  }
  EXPECT_EQ(scaled_jacobian(CellType::Hex, X), 1.0);
}

TEST(CornerJacobian, AffineMapScalesEveryCornerDeterminantByDetM) {
  // A_k -> M A_k under x -> M x, so det(A_k) -> det(M) det(A_k) at every corner of every type.
  Eigen::Matrix3d M;
  M << 1.3, 0.2, -0.1, 0.4, 0.9, 0.3, -0.2, 0.1, 1.1;
  const double detM = M.determinant();
  ASSERT_GT(detM, 0);
  const CornerValues hex = corner_determinants(CellType::Hex, mapped(ideal_cell(CellType::Hex), M));
  const CornerValues wedge = corner_determinants(CellType::Wedge, mapped(ideal_cell(CellType::Wedge), M));
  const CornerValues tet = corner_determinants(CellType::Tet, mapped(ideal_cell(CellType::Tet), M));
  const double h = std::sqrt(3.0) / 2;  // ideal triangle: height, 2 * area
  for (int k = 0; k < 8; ++k) EXPECT_NEAR(hex(k), detM, 1e-12);
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(wedge(k), h * detM, 1e-12);             // 2 * triangle area * prism height
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(tet(k), std::sqrt(0.5) * detM, 1e-12);  // 6 * volume = 6 sqrt(2) / 12
}

TEST(CornerJacobian, MirroredHexIsNegativeAtEveryCorner) {
  const CellNodes X = mapped(ideal_cell(CellType::Hex), Eigen::Vector3d(-1, 1, 1).asDiagonal());
  EXPECT_TRUE((corner_determinants(CellType::Hex, X).array() == -1.0).all());
  EXPECT_EQ(scaled_jacobian(CellType::Hex, X), -1.0);
}

TEST(CornerJacobian, NodePushedThroughOppositeFaceInvertsOnlyItsCorner) {
  // Node 0 moved from the origin past the plane x+y+z = 1 of its neighbours 1, 3, 4 to (0.6,0.6,0.6):
  // A_0 = I - 0.6 * 1 1^T, det = 1 - 3 * 0.6 = -0.8; the other corners stay positive.
  CellNodes X = ideal_cell(CellType::Hex);
  X.row(0).setConstant(0.6);
  const CornerValues d = corner_determinants(CellType::Hex, X);
  EXPECT_NEAR(d(0), -0.8, 1e-15);
  EXPECT_TRUE((d.tail(7).array() > 0).all());
  EXPECT_NEAR(min_corner_determinant(CellType::Hex, X), -0.8, 1e-15);
  EXPECT_LT(scaled_jacobian(CellType::Hex, X), 0);
}

TEST(CornerJacobian, ScaledJacobianOfStretchedAndShearedHexes) {
  // A box keeps orthogonal corner edges: 1. The shear x += s*y tilts the y edges by atan(s): 1 / sqrt(1 + s^2).
  EXPECT_NEAR(
      scaled_jacobian(CellType::Hex, mapped(ideal_cell(CellType::Hex), Eigen::Vector3d(2, 0.5, 3).asDiagonal())), 1,
      1e-15);
  const double s = 0.7;
  Eigen::Matrix3d shear = Eigen::Matrix3d::Identity();
  shear(0, 1) = s;
  EXPECT_NEAR(scaled_jacobian(CellType::Hex, mapped(ideal_cell(CellType::Hex), shear)), 1 / std::sqrt(1 + s * s),
              1e-15);
}

TEST(CornerJacobian, WedgeOrientationAndNormalization) {
  // Equilateral prism: every corner det / lengths = sin(60 deg), normalized to 1.
  EXPECT_TRUE((corner_determinants(CellType::Wedge, ideal_cell(CellType::Wedge)).head(6).array() > 0).all());
  EXPECT_NEAR(scaled_jacobian(CellType::Wedge, ideal_cell(CellType::Wedge)), 1, 1e-15);
  // Right prism: the 45 degree corners give sin(45) * 2 / sqrt(3) = sqrt(2/3).
  EXPECT_NEAR(scaled_jacobian(CellType::Wedge, right_prism()), std::sqrt(2.0 / 3), 1e-15);
  // Same nodes in the ANSYS/Gmsh order (triangle normal towards the other triangle): inverted everywhere.
  CellNodes reversed = ideal_cell(CellType::Wedge);
  reversed.row(1).swap(reversed.row(2));
  reversed.row(4).swap(reversed.row(5));
  EXPECT_TRUE((corner_determinants(CellType::Wedge, reversed).head(6).array() < 0).all());
  EXPECT_NEAR(scaled_jacobian(CellType::Wedge, reversed), -1, 1e-15);
}

TEST(CornerJacobian, RegularTetScaledJacobianIsOne) {
  EXPECT_NEAR(scaled_jacobian(CellType::Tet, ideal_cell(CellType::Tet)), 1, 1e-15);
  CellNodes flipped = ideal_cell(CellType::Tet);
  flipped.row(2).swap(flipped.row(3));
  EXPECT_NEAR(scaled_jacobian(CellType::Tet, flipped), -1, 1e-15);
}

TEST(CornerJacobian, MeshCheckListsExactlyTheInvertedCells) {
  VolumeMesh mesh = test::hex_box(3, 1, 1, 3, 1, 1);  // three unit cubes along x
  // Node 1 (x = 1, shared by cells 0 and 1) pushed to x = 2.5: cell 0 is stretched, cell 1 folds over.
  mesh.V(1, 0) = 2.5;
  const CornerJacobianCheck check = check_corner_jacobians(mesh);
  ASSERT_EQ(check.min_determinant.size(), 3);
  EXPECT_EQ(check.inverted, std::vector<int>({1}));
  EXPECT_GT(check.min_determinant(0), 0);
  // Corner 0 of cell 1 is the moved node; its edge to x = 2 became -0.5 x, the other two keep unit y and z parts.
  EXPECT_NEAR(check.min_determinant(1), -0.5, 1e-15);
  EXPECT_EQ(check.min_determinant(2), 1.0);
  EXPECT_TRUE(check.degenerate.empty());
}

TEST(CornerJacobian, InteriorSamplesOfIdealAndAffineCellsHaveTheAffineJacobian) {
  Eigen::Matrix3d M;
  M << 2, 0.3, 0, -0.1, 1.5, 0.2, 0.4, 0, 0.8;
  for (CellType type : {CellType::Hex, CellType::Wedge}) {
    const CellNodes ideal = ideal_cell(type);
    const CellNodes mapped = (ideal * M.transpose()).rowwise() + Eigen::RowVector3d(5, -2, 1);
    ASSERT_EQ(interior_sample_weights(type).size(), type == CellType::Hex ? 9u : 8u);
    for (const SampleWeights& W : interior_sample_weights(type)) {
      EXPECT_LT((ideal.transpose() * W - Eigen::Matrix3d::Identity()).norm(), 1e-12);
      EXPECT_LT((mapped.transpose() * W - M).norm(), 1e-12);
    }
  }
  EXPECT_TRUE(interior_sample_weights(CellType::Tet).empty());
}

// A hex from a mapped face mesh (coordinates in mm): all eight corners and the centre are positive, yet the trilinear
// map folds at a Gauss point, and CalculiX refused it ("nonpositive jacobian determinant"). It counts as inverted.
TEST(CornerJacobian, AHexFoldedOnlyAtAGaussPointIsInverted) {
  CellNodes X = CellNodes::Zero();
  X << 1.291, 2.400, 3.922, 2.273, 0.816, 0.000, 5.391, 1.512, 1.820, 1.453, 1.523, 2.427, 0.000, 3.827, 4.702, 1.618,
      0.000, 4.821, 5.173, 1.578, 3.924, 3.105, 4.356, 2.605;
  EXPECT_GT(corner_determinants(CellType::Hex, X).minCoeff(), 0);
  EXPECT_GT(hex_center_jacobian(X).determinant(), 0);
  EXPECT_GT(scaled_jacobian(CellType::Hex, X), 0.1);
  EXPECT_LE(min_corner_determinant(CellType::Hex, X), 0);
  VolumeMesh mesh;
  mesh.V = X;
  mesh.C = Eigen::RowVectorXi::LinSpaced(8, 0, 7);
  mesh.types = {CellType::Hex};
  EXPECT_EQ(check_corner_jacobians(mesh).inverted, std::vector<int>({0}));
}

TEST(CornerJacobian, AFlatCellIsDegenerateNotInverted) {
  VolumeMesh mesh = test::hex_box(2, 1, 1, 2, 1, 1);  // two unit cubes along x
  // Node (2,0,0), a corner of cell 1 only, moved almost onto the midpoint of its neighbours (2,1,0) and (2,0,1):
  // the face x = 2 is nearly folded flat, every corner determinant stays positive, but the scaled Jacobian is ~1e-8.
  const int corner = 2, a = 5, b = 8;
  const double t = 1 - 1e-8;
  mesh.V.row(corner) = (1 - t) * mesh.V.row(corner) + t * 0.5 * (mesh.V.row(a) + mesh.V.row(b));
  const CornerJacobianCheck check = check_corner_jacobians(mesh);
  EXPECT_TRUE(check.inverted.empty());
  EXPECT_EQ(check.degenerate, std::vector<int>({1}));
  EXPECT_EQ(check.unusable(), std::vector<int>({1}));
  EXPECT_LT(scaled_jacobian(CellType::Hex, cell_nodes(mesh, 1)), kDegenerateScaledJacobian);
  EXPECT_TRUE(is_unusable(CellType::Hex, cell_nodes(mesh, 1)));
  EXPECT_FALSE(is_unusable(CellType::Hex, cell_nodes(mesh, 0)));
}

// cell_jacobians (one pass) gives the scaled Jacobian and the smallest corner or sample determinant as their
// definitions give them apart, on cells pushed about at random until some are inverted, for every cell type.
TEST(CornerJacobian, OnePassGivesTheSeparateMeasures) {
  std::srand(7);
  int inverted = 0;
  for (CellType type : {CellType::Tet, CellType::Wedge, CellType::Hex})
    for (int trial = 0; trial < 200; ++trial) {
      CellNodes X = ideal_cell(type);
      X.topRows(node_count(type)) += 0.45 * Eigen::MatrixXd::Random(node_count(type), 3);
      const CellJacobians j = cell_jacobians(type, X);
      // Scaled Jacobian by its definition: the corners (and a hex's centre), each det / edge lengths, normalized.
      auto unit = [](const Eigen::Matrix3d& A) {
        const double lengths = A.col(0).norm() * A.col(1).norm() * A.col(2).norm();
        return lengths > 0 ? A.determinant() / lengths : 0.0;
      };
      double scaled = 1;
      for (int k = 0; k < node_count(type); ++k) scaled = std::min(scaled, unit(corner_jacobian(type, X, k)));
      if (type == CellType::Hex) scaled = std::min(scaled, unit(hex_center_jacobian(X)));
      scaled *= type == CellType::Tet ? std::sqrt(2.0) : type == CellType::Wedge ? 2 / std::sqrt(3.0) : 1.0;
      EXPECT_DOUBLE_EQ(j.scaled_jacobian, scaled);
      EXPECT_EQ(scaled_jacobian(type, X), j.scaled_jacobian);
      double lowest = corner_determinants(type, X).head(node_count(type)).minCoeff();
      for (const SampleWeights& W : interior_sample_weights(type))
        lowest = std::min(lowest, (X.transpose() * W).determinant());
      EXPECT_EQ(j.min_determinant, lowest);
      EXPECT_EQ(is_unusable(j), lowest <= 0 || j.scaled_jacobian < kDegenerateScaledJacobian);
      inverted += lowest <= 0;
    }
  EXPECT_GT(inverted, 10);  // the inverted branch was exercised
}

}  // namespace
}  // namespace facehex
