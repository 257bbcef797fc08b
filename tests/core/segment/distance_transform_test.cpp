#include "core/segment/distance_transform.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "core/segment/morphology.h"

namespace facehex {
namespace {

// The distance from voxel (i, j, k) to the nearest feature voxel, by comparing with every one.
double brute_force_distance(const Mask& features, int i, int j, int k) {
  const GridGeometry& g = features.geometry;
  double best = std::numeric_limits<double>::infinity();
  for (size_t f = 0; f < g.size(); ++f)
    if (features.data[f]) {
      const auto [a, b, c] = g.ijk(f);
      best = std::min(best, (g.point(i, j, k) - g.point(a, b, c)).norm());
    }
  return best;
}

TEST(DistanceTransform, MatchesBruteForceOnAnAnisotropicGrid) {
  GridGeometry g;
  g.dims = {9, 7, 6};
  g.spacing = Eigen::Vector3d(0.7, 1.3, 2.1);
  Mask features(g, 0);
  features(1, 1, 1) = features(7, 2, 4) = features(3, 6, 0) = 1;
  std::vector<std::int64_t> nearest;
  const Field d = distance_to(features, &nearest);
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const double best = brute_force_distance(features, i, j, k);
        ASSERT_NEAR(d(i, j, k), best, 1e-5);
        const auto [a, b, c] = g.ijk(static_cast<size_t>(nearest[g.index(i, j, k)]));
        EXPECT_NEAR((g.point(i, j, k) - g.point(a, b, c)).norm(), best, 1e-5);
      }
}

// Lines along y and z are transformed several neighbours in x at a time: a grid wider than one such block, with a
// partial block at its end, and features scattered by a fixed seed.
TEST(DistanceTransform, MatchesBruteForceAcrossBlocksOfLines) {
  GridGeometry g;
  g.dims = {37, 11, 9};
  g.spacing = Eigen::Vector3d(1.0, 0.8, 1.7);
  Mask features(g, 0);
  std::mt19937 random(7);
  for (int n = 0; n < 12; ++n) features.data[random() % g.size()] = 1;
  const Field d = distance_to(features);
  for (size_t v = 0; v < g.size(); ++v) {
    const auto [i, j, k] = g.ijk(v);
    ASSERT_NEAR(d.data[v], brute_force_distance(features, i, j, k), 1e-5) << i << " " << j << " " << k;
  }
}

// within_distance is the threshold of distance_to, voxel for voxel, also at radii that voxel distances meet exactly.
TEST(DistanceTransform, WithinDistanceIsTheThresholdedDistance) {
  GridGeometry g;
  g.dims = {23, 19, 17};
  g.spacing = Eigen::Vector3d(1.0, 1.0, 0.7);
  Mask features(g, 0);
  features(11, 9, 8) = features(2, 3, 4) = features(20, 17, 1) = 1;
  const Field d = distance_to(features);
  for (const double radius : {0.0, 0.7, 1.0, std::sqrt(2.0), 2.0, 3.5, 5.0, 100.0, -1.0}) {
    const Mask within = within_distance(features, radius);
    for (size_t v = 0; v < g.size(); ++v) ASSERT_EQ(within.data[v], d.data[v] <= radius) << radius << " at " << v;
  }
}

TEST(DistanceTransform, EmptyMaskIsInfinitelyFar) {
  GridGeometry g;
  g.dims = {3, 3, 3};
  const Field d = distance_to(Mask(g, 0));
  for (float v : d.data) EXPECT_TRUE(std::isinf(v));
  const Mask within = within_distance(Mask(g, 0), 1e6);
  for (auto v : within.data) EXPECT_EQ(v, 0);
}

constexpr std::array<bool, 6> kAllOpen = {true, true, true, true, true, true};

TEST(Morphology, FillCavitiesKeepsOpenAirAndFillsEnclosedAir) {
  GridGeometry g;
  g.dims = {9, 9, 9};
  Mask shell(g, 0);
  for (int k = 1; k < 8; ++k)
    for (int j = 1; j < 8; ++j)
      for (int i = 1; i < 8; ++i) shell(i, j, k) = (i == 1 || i == 7 || j == 1 || j == 7 || k == 1 || k == 7);
  const Mask filled = fill_cavities(shell, kAllOpen);
  EXPECT_EQ(filled(4, 4, 4), 1);
  EXPECT_EQ(filled(0, 4, 4), 0);
  // A hole in the shell lets the cavity out.
  Mask open_shell = shell;
  open_shell(7, 4, 4) = 0;
  EXPECT_EQ(fill_cavities(open_shell, kAllOpen)(4, 4, 4), 0);
  // Air that only reaches a face that is not open (the trachea at the bottom slice) is filled.
  Mask tube(g, 1);
  for (int k = 0; k < 5; ++k) tube(4, 4, k) = 0;
  EXPECT_EQ(fill_cavities(tube, {true, true, true, true, false, true})(4, 4, 2), 1);
  EXPECT_EQ(fill_cavities(tube, kAllOpen)(4, 4, 2), 0);
  // Each face on its own: air reaching the -y face only (an airway where the scan ends behind the face) is filled
  // when that face is closed, whatever the others.
  Mask airway(g, 1);
  for (int j = 0; j < 5; ++j) airway(4, j, 4) = 0;
  EXPECT_EQ(fill_cavities(airway, {true, true, false, true, true, true})(4, 2, 4), 1);
  EXPECT_EQ(fill_cavities(airway, {false, false, true, false, false, false})(4, 2, 4), 0);
}

TEST(Morphology, OpeningDropsThinAttachmentsAndClosingFillsNarrowGaps) {
  GridGeometry g;
  g.dims = {30, 20, 20};
  Mask m(g, 0);
  for (int k = 3; k < 17; ++k)
    for (int j = 3; j < 17; ++j)
      for (int i = 3; i < 17; ++i) m(i, j, k) = 1;  // a 14-voxel cube
  for (int i = 17; i < 28; ++i) m(i, 10, 10) = 1;   // a 1-voxel-thin rod stuck to it
  const Mask opened = open(m, 2.0);
  EXPECT_EQ(opened(25, 10, 10), 0);
  EXPECT_EQ(opened(10, 10, 10), 1);
  Mask gap = m;
  for (int j = 3; j < 17; ++j)
    for (int k = 3; k < 17; ++k) gap(10, j, k) = 0;  // a 1-voxel slit through the cube
  const Mask closed = close(gap, 1.5);
  EXPECT_EQ(closed(10, 10, 10), 1);
  EXPECT_EQ(closed(1, 10, 10), 0);
  // Where the mask is cut by the grid, closing does not eat into it.
  Mask slab(g, 0);
  for (int k = 0; k < 20; ++k)
    for (int j = 5; j < 15; ++j)
      for (int i = 5; i < 25; ++i) slab(i, j, k) = 1;
  const Mask closed_slab = close(slab, 3.0);
  EXPECT_EQ(closed_slab(10, 10, 0), 1);
  EXPECT_EQ(closed_slab(10, 10, 19), 1);
}

}  // namespace
}  // namespace facehex
