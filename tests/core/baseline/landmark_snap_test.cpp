// The local displacement that carries registered landmarks exactly onto their targets.
#include "core/baseline/landmark_snap.h"

#include <gtest/gtest.h>

#include <random>

#include "core/util/error.h"

namespace facehex {
namespace {

Eigen::MatrixXd grid_points(double spacing, int n) {
  Eigen::MatrixXd X(n * n * n, 3);
  int row = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) X.row(row++) << i * spacing, j * spacing, k * spacing;
  return X;
}

// Each landmark lands exactly on its target, whatever the others (several seeds, landmarks 8 to 40 mm apart); points
// beyond the radius from every landmark stay; the displacement is continuous (no jump between close points).
TEST(LandmarkSnap, CarriesEachLandmarkOntoItsTargetAndNothingBeyondTheRadius) {
  for (unsigned seed : {1u, 2u, 3u}) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> along(20, 80), residual(-3, 3);
    Eigen::MatrixXd from(6, 3), to(6, 3);
    for (int i = 0; i < 6; ++i) {
      from.row(i) << along(rng), along(rng), along(rng);
      to.row(i) = from.row(i) + Eigen::RowVector3d(residual(rng), residual(rng), residual(rng));
    }
    const double radius = 25;
    const Eigen::MatrixXd snapped = landmark_snap(from, from, to, radius);
    EXPECT_LT((snapped - to).cwiseAbs().maxCoeff(), 1e-9) << "seed " << seed;
    const Eigen::MatrixXd X = grid_points(5, 21);  // 0 to 100 mm
    const Eigen::MatrixXd Y = landmark_snap(X, from, to, radius);
    for (Eigen::Index k = 0; k < X.rows(); ++k) {
      double nearest = 1e9;
      for (int i = 0; i < 6; ++i) nearest = std::min(nearest, (X.row(k) - from.row(i)).norm());
      if (nearest >= radius) {
        EXPECT_EQ((Y.row(k) - X.row(k)).norm(), 0.0);
      }
      EXPECT_LT((Y.row(k) - X.row(k)).norm(), 10.0);  // bounded: no landmark asks for more than 5.2 mm
    }
    const Eigen::MatrixXd near = landmark_snap(from.rowwise() + Eigen::RowVector3d(1e-4, 0, 0), from, to, radius);
    EXPECT_LT((near - snapped).cwiseAbs().maxCoeff(), 1e-3);
  }
}

// No landmark: nothing moves. A landmark given twice with the same target is one; with two targets, or with no
// radius, an error; lists of unequal length are refused.
TEST(LandmarkSnap, BadLandmarksAreErrors) {
  const Eigen::MatrixXd X = grid_points(10, 3);
  EXPECT_EQ(landmark_snap(X, Eigen::MatrixXd(0, 3), Eigen::MatrixXd(0, 3), 25), X);
  Eigen::MatrixXd from(2, 3), to(2, 3);
  from << 10, 10, 10, 10, 10, 10;
  to << 12, 10, 10, 12, 10, 10;
  EXPECT_LT((landmark_snap(from, from, to, 25) - to).norm(), 1e-12);
  to.row(1) << 8, 10, 10;
  EXPECT_THROW(landmark_snap(X, from, to, 25), Error);
  EXPECT_THROW(landmark_snap(X, from.topRows(1), to.topRows(1), 0), Error);
  EXPECT_THROW(landmark_snap(X, from, to.topRows(1), 25), Error);
}

}  // namespace
}  // namespace facehex
