#include "core/mesh/tet_topology.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace facehex {
namespace {

// Vertices of a unit tet (0..3), an apex on the other side of face 1-2-3 (4), and a far tet (5..8).
Eigen::MatrixXd points() {
  return (Eigen::MatrixXd(9, 3) << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1, 5, 5, 5, 6, 5, 5, 5, 6, 5, 5, 5, 6)
      .finished();
}

TEST(TetTopology, TwoTetsShareOneFaceAndAFarTetIsAnotherComponent) {
  const Eigen::MatrixXi T = (Eigen::MatrixXi(3, 4) << 0, 1, 2, 3, 4, 2, 1, 3, 5, 6, 7, 8).finished();
  const TetFaceAdjacency a = tet_face_adjacency(T);
  // Tet 0's face opposite vertex 0 (1-2-3) is tet 1's face opposite its vertex 0 (the apex 4).
  EXPECT_EQ(a.neighbors(0, 0), 1);
  EXPECT_EQ(a.neighbors(1, 0), 0);
  EXPECT_EQ((a.neighbors.array() >= 0).count(), 2);
  EXPECT_EQ(a.boundary.F.rows(), 3 * 4 - 2);
  EXPECT_EQ(a.boundary.nonmanifold_faces, 0);
  Eigen::VectorXi component;
  EXPECT_EQ(tet_components(a.neighbors, component), 2);
  EXPECT_EQ(component(0), component(1));
  EXPECT_NE(component(0), component(2));
  // Each boundary face is outward: its normal points away from the rest of its tet.
  const Eigen::MatrixXd V = points();
  for (Eigen::Index f = 0; f < a.boundary.F.rows(); ++f) {
    const Eigen::Vector3d p0 = V.row(a.boundary.F(f, 0)), p1 = V.row(a.boundary.F(f, 1)),
                          p2 = V.row(a.boundary.F(f, 2));
    const Eigen::Vector3d n = (p1 - p0).cross(p2 - p0);
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) centre += V.row(T(a.boundary.tet(f), k)).transpose() / 4;
    EXPECT_LT(n.dot(centre - p0), 0) << "face " << f;
  }
  // The two wrappers return the same parts.
  EXPECT_EQ(tet_face_neighbors(T), a.neighbors);
  EXPECT_EQ(boundary_faces(T).F, a.boundary.F);
}

TEST(TetTopology, AFaceOfThreeTetsIsNonManifoldAndNotABoundary) {
  // Three tets on face 1-2-3: 0 below it, the apex 4 above, and a third apex (5, far out) above too.
  const Eigen::MatrixXi T = (Eigen::MatrixXi(3, 4) << 0, 1, 2, 3, 4, 2, 1, 3, 5, 2, 1, 3).finished();
  const TetFaceAdjacency a = tet_face_adjacency(T);
  EXPECT_EQ(a.boundary.nonmanifold_faces, 1);
  EXPECT_EQ(a.boundary.F.rows(), 3 * 3);
  EXPECT_EQ((a.neighbors.array() >= 0).count(), 0);  // the shared face joins no pair
}

}  // namespace
}  // namespace facehex
