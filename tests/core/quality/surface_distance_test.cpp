// Closest points on a triangle surface and where a line through a point meets it (surface_distance.h).
#include "core/quality/surface_distance.h"

#include <gtest/gtest.h>

#include <cmath>

namespace facehex {
namespace {

// The square [0, 10]^2 at z = 0 in two triangles.
struct Square {
  Eigen::MatrixXd V{{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}};
  Eigen::MatrixXi F{{0, 1, 2}, {0, 2, 3}};
};

TEST(SurfaceLocator, ClosestPointsOnASquare) {
  const Square s;
  const Eigen::MatrixXd P{{3, 4, 2}, {12, 5, 0}};
  const SurfaceLocator::Hits h = SurfaceLocator(s.V, s.F).closest(P);
  EXPECT_LT((h.point.row(0) - Eigen::RowVector3d(3, 4, 0)).norm(), 1e-12);
  EXPECT_NEAR(h.distance(0), 2, 1e-12);
  EXPECT_LT((h.point.row(1) - Eigen::RowVector3d(10, 5, 0)).norm(), 1e-12);
  EXPECT_NEAR(h.distance(1), 2, 1e-12);
}

// Along a line: the nearer crossing either way, within the reach; nothing where the line misses or the surface is
// farther than the reach, or the direction is zero.
TEST(SurfaceLocator, WhereALineThroughAPointMeetsTheSurface) {
  const Square s;
  const SurfaceLocator locator(s.V, s.F);
  const Eigen::MatrixXd P{{3, 4, 2}, {6, 7, -1.5}, {3, 4, 20}, {12, 5, 1}};
  const Eigen::Vector3d slanted = Eigen::Vector3d(1, 0, -1).normalized();
  const SurfaceLocator::Hits h = locator.along(P, Eigen::Vector3d::UnitZ(), 5);
  EXPECT_LT((h.point.row(0) - Eigen::RowVector3d(3, 4, 0)).norm(), 1e-9);
  EXPECT_NEAR(h.distance(0), 2, 1e-9);
  EXPECT_LT((h.point.row(1) - Eigen::RowVector3d(6, 7, 0)).norm(), 1e-9);
  EXPECT_NEAR(h.distance(1), 1.5, 1e-9);
  EXPECT_EQ(h.face(2), -1);  // 20 above: beyond the reach
  EXPECT_EQ(h.point.row(2), P.row(2));
  EXPECT_TRUE(std::isinf(h.distance(2)));
  EXPECT_EQ(h.face(3), -1);  // beside the square
  const SurfaceLocator::Hits tilted = locator.along(P.topRows(1), slanted, 5);
  EXPECT_LT((tilted.point.row(0) - Eigen::RowVector3d(5, 4, 0)).norm(), 1e-9);
  EXPECT_NEAR(tilted.distance(0), 2 * std::sqrt(2.0), 1e-9);
  EXPECT_EQ(locator.along(P, Eigen::Vector3d::Zero(), 5).face.maxCoeff(), -1);
}

}  // namespace
}  // namespace facehex
