// The material frame of a cell: exact for affinely mapped cells, orthonormal and right-handed always, with the sign
// conventions of material_frame.h.
#include "core/mesh/material_frame.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "core/mesh/corner_jacobian.h"

namespace facehex {
namespace {

// One cell of `type` (the ideal cell of corner_jacobian.h) whose vertices carry uvw = their reference position,
// mapped by x = A p + t.
VolumeMesh mapped_cell(CellType type, const Eigen::Matrix3d& A, Eigen::MatrixXd* uvw) {
  const int n = node_count(type);
  const CellNodes P = ideal_cell(type);
  VolumeMesh m;
  m.V = (P.topRows(n) * A.transpose()).rowwise() + Eigen::RowVector3d(3, -2, 7);
  m.C = Eigen::MatrixXi::Constant(1, 8, -1);
  for (int k = 0; k < n; ++k) m.C(0, k) = k;
  m.types = {type};
  *uvw = P.topRows(n);
  return m;
}

Eigen::Matrix3d frame_of(const MaterialFrames& f, int c) {
  Eigen::Matrix3d F;
  F << f.e1.row(c).transpose(), f.e2.row(c).transpose(), f.e3.row(c).transpose();
  return F;
}

const Eigen::Matrix3d kRotation =
    (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()) * Eigen::AngleAxisd(-0.3, Eigen::Vector3d::UnitX()))
        .toRotationMatrix();

TEST(MaterialFrame, RotatedAndScaledCellsGiveTheRotatedAxesExactly) {
  // x = R S p: the gradients of u, v, w are the columns of R divided by the scales, so the frame is R itself.
  const Eigen::Matrix3d A = kRotation * Eigen::Vector3d(4, 0.5, 2).asDiagonal();
  for (CellType type : {CellType::Hex, CellType::Wedge, CellType::Tet}) {
    Eigen::MatrixXd uvw;
    const VolumeMesh m = mapped_cell(type, A, &uvw);
    const MaterialFrames f = material_frames(m, uvw);
    EXPECT_TRUE(f.degenerate.empty());
    EXPECT_LT((frame_of(f, 0) - kRotation).cwiseAbs().maxCoeff(), 1e-12) << cell_type_name(type);
  }
}

TEST(MaterialFrame, FaceConventionFlipsE1) {
  // u along +x, v along +z, w along +y (the face looks towards +y): (grad u, grad v, grad w) is left-handed, so e1
  // points to -x while e2 and e3 keep the directions of increasing v and w.
  Eigen::Matrix3d A;
  A.col(0) = 10 * Eigen::Vector3d::UnitX();
  A.col(1) = 8 * Eigen::Vector3d::UnitZ();
  A.col(2) = 3 * Eigen::Vector3d::UnitY();
  Eigen::MatrixXd uvw;
  const VolumeMesh m = mapped_cell(CellType::Hex, A, &uvw);
  const MaterialFrames f = material_frames(m, uvw);
  EXPECT_LT((f.e1.row(0) - Eigen::RowVector3d(-1, 0, 0)).norm(), 1e-12);
  EXPECT_LT((f.e2.row(0) - Eigen::RowVector3d(0, 0, 1)).norm(), 1e-12);
  EXPECT_LT((f.e3.row(0) - Eigen::RowVector3d(0, 1, 0)).norm(), 1e-12);
}

TEST(MaterialFrame, ShearedCellKeepsDepthExactAndOrthonormalizesTheRest) {
  // A general affine map: e3 is exactly along grad w, e1 lies in the plane of grad u and grad w, and the frame is a
  // rotation.
  Eigen::Matrix3d A;
  A << 3, 0.8, -0.4, 0.5, 2, 0.3, 0.2, -0.6, 1.5;
  Eigen::MatrixXd uvw;
  const VolumeMesh m = mapped_cell(CellType::Hex, A, &uvw);
  const Eigen::Matrix3d F = frame_of(material_frames(m, uvw), 0);
  const Eigen::Matrix3d G = A.inverse();  // rows: gradients of u, v, w
  EXPECT_LT((F.transpose() * F - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NEAR(F.determinant(), 1.0, 1e-12);
  EXPECT_LT((F.col(2) - G.row(2).transpose().normalized()).norm(), 1e-12);
  EXPECT_NEAR(F.col(0).dot(G.row(0).transpose().cross(G.row(2).transpose())), 0.0, 1e-12);
  EXPECT_GT(F.col(1).dot(G.row(1).transpose()), 0);
}

TEST(MaterialFrame, GradientIsExactForAffineDataOnADistortedHex) {
  CellNodes X = ideal_cell(CellType::Hex);
  X.row(6) += Eigen::RowVector3d(0.3, -0.2, 0.25);
  Eigen::Matrix3d G;
  G << 1, 2, 3, -1, 0.5, 0, 0.2, 0.1, -4;
  const Eigen::MatrixXd P = (X * G.transpose()).rowwise() + Eigen::RowVector3d(0.1, 0.2, 0.3);
  EXPECT_LT((parametric_gradient(X, P) - G).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(MaterialFrame, DegenerateParameterizationIsReportedWithGlobalAxes) {
  Eigen::MatrixXd uvw;
  const VolumeMesh m = mapped_cell(CellType::Wedge, Eigen::Matrix3d::Identity(), &uvw);
  uvw.col(1) = uvw.col(0);  // v = u: no up direction
  const MaterialFrames f = material_frames(m, uvw);
  EXPECT_EQ(f.degenerate, std::vector<int>{0});
  EXPECT_EQ(frame_of(f, 0), Eigen::Matrix3d::Identity());
  EXPECT_FALSE(frame_from_gradient(Eigen::Matrix3d::Zero()));
}

}  // namespace
}  // namespace facehex
