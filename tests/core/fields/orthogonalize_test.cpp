#include "core/fields/orthogonalize.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <limits>
#include <random>

namespace facehex {
namespace {

// One tet's three gradients as a GradientFields of one row.
GradientFields one_tet(const Eigen::Vector3d& u, const Eigen::Vector3d& v, const Eigen::Vector3d& w) {
  GradientFields g;
  for (auto& m : g) m.resize(1, 3);
  g[0].row(0) = u.transpose();
  g[1].row(0) = v.transpose();
  g[2].row(0) = w.transpose();
  return g;
}

Eigen::Vector3d row(const Eigen::MatrixXd& m, Eigen::Index i) { return m.row(i).transpose(); }

GradientFields random_fields(int tets, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-2.0, 2.0);
  GradientFields g;
  for (auto& m : g) {
    m.resize(tets, 3);
    for (Eigen::Index i = 0; i < m.size(); ++i) m(i) = d(rng);
  }
  return g;
}

TEST(OrthogonalTargets, AnOrthogonalFrameIsLeftAsItIsInEveryOrder) {
  const GradientFields g = one_tet({2, 0, 0}, {0, -3, 0}, {0, 0, 0.5});
  for (const std::array<int, 3>& order : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{2, 0, 1},
                                          std::array<int, 3>{1, 2, 0}, std::array<int, 3>{0, 2, 1}}) {
    const GradientFields t = orthogonal_targets(g, order);
    for (int f = 0; f < 3; ++f)
      EXPECT_LT((t[f] - g[f]).norm(), 1e-15) << "field " << f << " order " << order[0] << order[1] << order[2];
  }
}

TEST(OrthogonalTargets, KeepsTheBasicProjectsTheSecondAndCrossesTheThird) {
  // u basic along x; v at 45 degrees in the xy plane: its projection (0, 1, 0) scaled to |v| = sqrt(2);
  // w replaced by x cross y = z scaled to |w|, kept on w's side (w . z > 0).
  const Eigen::Vector3d w(0.3, -0.2, 5.0);
  const GradientFields t = orthogonal_targets(one_tet({3, 0, 0}, {1, 1, 0}, w), {0, 1, 2});
  EXPECT_LT((row(t[0], 0) - Eigen::Vector3d(3, 0, 0)).norm(), 1e-15);
  EXPECT_LT((row(t[1], 0) - Eigen::Vector3d(0, std::sqrt(2.0), 0)).norm(), 1e-15);
  EXPECT_LT((row(t[2], 0) - Eigen::Vector3d(0, 0, w.norm())).norm(), 1e-14);
}

TEST(OrthogonalTargets, TheThirdKeepsItsOrientation) {
  // The same frame with w pointing down: x cross y = +z would reverse it, so the target is -z * |w|.
  const GradientFields t = orthogonal_targets(one_tet({1, 0, 0}, {1, 1, 0}, {0.1, 0.1, -2}), {0, 1, 2});
  EXPECT_LT((row(t[2], 0) - Eigen::Vector3d(0, 0, -std::sqrt(4.02))).norm(), 1e-14);
}

TEST(OrthogonalTargets, TheOrderPicksWhichFieldIsKept) {
  // Basic w (along z), second u, third v: u = (1, 0, 1) loses its z part, v becomes z cross x = y (scaled).
  const GradientFields t = orthogonal_targets(one_tet({1, 0, 1}, {0.5, 2, 0.5}, {0, 0, 4}), {2, 0, 1});
  EXPECT_LT((row(t[2], 0) - Eigen::Vector3d(0, 0, 4)).norm(), 1e-15);
  EXPECT_LT((row(t[0], 0) - Eigen::Vector3d(std::sqrt(2.0), 0, 0)).norm(), 1e-14);
  EXPECT_LT((row(t[1], 0) - Eigen::Vector3d(0, std::sqrt(4.5), 0)).norm(), 1e-14);
}

TEST(OrthogonalTargets, RandomFramesBecomeOrthogonalWithTheirNormsAndOrientations) {
  const GradientFields g = random_fields(500, 3);
  for (const std::array<int, 3>& order :
       {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{1, 2, 0}, std::array<int, 3>{2, 1, 0}}) {
    const auto [b, s, third] = order;
    const GradientFields t = orthogonal_targets(g, order);
    for (int f = 0; f < 3; ++f) ASSERT_EQ(t[f].rows(), 500);
    for (int i = 0; i < 500; ++i) {
      const Eigen::Vector3d tb = row(t[b], i), ts = row(t[s], i), tt = row(t[third], i);
      EXPECT_EQ(tb, row(g[b], i));  // the basic gradient is kept bit for bit
      for (int f = 0; f < 3; ++f) EXPECT_NEAR(row(t[f], i).norm(), row(g[f], i).norm(), 1e-12);
      EXPECT_NEAR(tb.dot(ts), 0, 1e-12);
      EXPECT_NEAR(tb.dot(tt), 0, 1e-12);
      EXPECT_NEAR(ts.dot(tt), 0, 1e-12);
      EXPECT_GE(tt.dot(row(g[third], i)), 0);
      // The second stays in the plane of the basic and the original second, on the original's side.
      EXPECT_NEAR(ts.dot(tb.cross(row(g[s], i))), 0, 1e-10);
      EXPECT_GT(ts.dot(row(g[s], i)), 0);
    }
    const Eigen::MatrixXd angles = gradient_angles(t);
    EXPECT_LT((angles.array() - 90).abs().maxCoeff(), 1e-9);
    const AngleStatistics stats = angle_statistics(angles);
    EXPECT_EQ(stats.angles, 1500);
    // 90 degrees up to round-off: the last bin below 90 or the first above.
    EXPECT_EQ(stats.histogram[8] + stats.histogram[9], 1500);
    EXPECT_LT(stats.mean_deviation_from_90, 1e-9);
    EXPECT_EQ(stats.fraction_within_10_of_90, 1.0);
  }
}

TEST(OrthogonalTargets, TetsWithoutABasicOrWithAParallelSecondAreLeftAlone) {
  GradientFields g = random_fields(3, 5);
  g[0].row(0).setZero();   // tet 0: no basic direction
  g[0].row(1) << 0, 2, 0;  // tet 1: second exactly parallel to the basic, the projection exactly zero
  g[1].row(1) << 0, -5, 0;
  const GradientFields t = orthogonal_targets(g, {0, 1, 2});
  for (int f = 0; f < 3; ++f) {
    EXPECT_EQ(row(t[f], 0), row(g[f], 0)) << "field " << f;
    EXPECT_EQ(row(t[f], 1), row(g[f], 1)) << "field " << f;
  }
  EXPECT_NEAR(row(t[0], 2).dot(row(t[1], 2)), 0, 1e-12);  // tet 2 is orthogonalized as usual
}

TEST(GradientAngles, PairsAreUvVwUwInDegrees) {
  // u = x, v at 60 degrees from u in the xy plane, w = -x: (u,v) 60, (v,w) 120, (u,w) 180.
  const GradientFields g = one_tet({2, 0, 0}, {0.5, std::sqrt(0.75), 0}, {-1, 0, 0});
  const Eigen::MatrixXd a = gradient_angles(g);
  ASSERT_EQ(a.rows(), 1);
  ASSERT_EQ(a.cols(), 3);
  EXPECT_NEAR(a(0, 0), 60, 1e-12);
  EXPECT_NEAR(a(0, 1), 120, 1e-12);
  EXPECT_NEAR(a(0, 2), 180, 1e-12);
}

TEST(GradientAngles, AVanishingGradientGivesNaNForItsPairsOnly) {
  const Eigen::MatrixXd a = gradient_angles(one_tet({1, 0, 0}, {0, 0, 0}, {1, 1, 0}));
  EXPECT_TRUE(std::isnan(a(0, 0)));
  EXPECT_TRUE(std::isnan(a(0, 1)));
  EXPECT_NEAR(a(0, 2), 45, 1e-12);
}

TEST(AngleStatistics, HistogramMeanDeviationAndFractionOfKnownAngles) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Eigen::MatrixXd angles(4, 3);
  angles << 0, 5, 10,  //
      80, 90, 95,      //
      100.5, 179.9, 180, nan, nan, 45;
  const AngleStatistics s = angle_statistics(angles);
  ASSERT_EQ(s.histogram.size(), 18u);
  EXPECT_EQ(s.angles, 10);  // the two NaNs are left out
  std::vector<long> expected(18, 0);
  expected[0] = 2;   // 0, 5
  expected[1] = 1;   // 10
  expected[4] = 1;   // 45
  expected[8] = 1;   // 80
  expected[9] = 2;   // 90, 95
  expected[10] = 1;  // 100.5
  expected[17] = 2;  // 179.9 and 180 (the last bin is closed)
  EXPECT_EQ(s.histogram, expected);
  const double deviation = 90 + 85 + 80 + 10 + 0 + 5 + 10.5 + 89.9 + 90 + 45;
  EXPECT_NEAR(s.mean_deviation_from_90, deviation / 10, 1e-12);
  EXPECT_NEAR(s.fraction_within_10_of_90, 0.3, 1e-15);  // 80, 90, 95: the 10 degree bound is inclusive
}

TEST(AngleStatistics, NoAnglesGiveZeros) {
  const AngleStatistics s = angle_statistics(Eigen::MatrixXd::Constant(2, 3, std::numeric_limits<double>::quiet_NaN()));
  EXPECT_EQ(s.angles, 0);
  EXPECT_EQ(s.histogram, std::vector<long>(18, 0));
  EXPECT_EQ(s.mean_deviation_from_90, 0);
  EXPECT_EQ(s.fraction_within_10_of_90, 0);
}

}  // namespace
}  // namespace facehex
