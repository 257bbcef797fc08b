// Connected components of a voxel mask against a plain flood fill: the same labels (components numbered in the order
// of their first voxel in memory) and sizes on random masks of several densities and odd sizes.
#include "core/segment/morphology.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <deque>
#include <random>
#include <vector>

namespace facehex {
namespace {

// The reference: a breadth-first flood fill from each unlabelled mask voxel in memory order, over the 6 face
// neighbours.
int flood_fill_labels(const Mask& mask, std::vector<int>& labels, std::vector<size_t>& sizes) {
  const GridGeometry& g = mask.geometry;
  labels.assign(g.size(), 0);
  sizes.assign(1, 0);
  int n = 0;
  std::deque<size_t> queue;
  for (size_t seed = 0; seed < g.size(); ++seed) {
    if (!mask.data[seed] || labels[seed]) continue;
    labels[seed] = ++n;
    sizes.push_back(0);
    queue.push_back(seed);
    while (!queue.empty()) {
      const size_t v = queue.front();
      queue.pop_front();
      ++sizes[n];
      const auto [i, j, k] = g.ijk(v);
      const int step[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
      for (const auto& s : step) {
        const int a = i + s[0], b = j + s[1], c = k + s[2];
        if (!g.contains(a, b, c)) continue;
        const size_t w = g.index(a, b, c);
        if (mask.data[w] && !labels[w]) labels[w] = n, queue.push_back(w);
      }
    }
  }
  return n;
}

TEST(Morphology, ComponentsAreThoseOfAFloodFillInTheSameOrder) {
  for (const double density : {0.2, 0.35, 0.5, 0.65, 0.9})
    for (const std::uint32_t seed : {1u, 2u, 3u}) {
      GridGeometry g;
      g.dims = {17, 13, 11};
      Mask mask(g, 0);
      std::mt19937 random(seed);
      std::bernoulli_distribution in(density);
      for (auto& v : mask.data) v = in(random) ? 1 : 0;
      std::vector<int> labels, expected_labels;
      std::vector<size_t> sizes, expected_sizes;
      const int n = label_components(mask, labels, sizes);
      EXPECT_EQ(n, flood_fill_labels(mask, expected_labels, expected_sizes)) << density << " " << seed;
      EXPECT_EQ(labels, expected_labels) << density << " " << seed;
      EXPECT_EQ(sizes, expected_sizes) << density << " " << seed;
    }
}

// A ring in one slice and a U shape whose arms meet only through the slice above: one component each, found although
// their runs first meet far from where each began.
TEST(Morphology, ShapesJoinedLateAreOneComponent) {
  GridGeometry g;
  g.dims = {12, 12, 3};
  Mask mask(g, 0);
  for (int i = 1; i <= 5; ++i)
    for (int j = 1; j <= 5; ++j)
      if (i == 1 || i == 5 || j == 1 || j == 5) mask(i, j, 0) = 1;  // a ring
  for (int j = 1; j <= 8; ++j) mask(8, j, 0) = mask(10, j, 0) = 1;  // two bars
  for (int i = 8; i <= 10; ++i) mask(i, 8, 1) = 1;                  // joined above their far end
  mask(8, 8, 1) = mask(10, 8, 1) = 1;
  std::vector<int> labels;
  std::vector<size_t> sizes;
  ASSERT_EQ(label_components(mask, labels, sizes), 2);
  EXPECT_EQ(sizes[1], 16u);
  EXPECT_EQ(sizes[2], 8u + 8u + 3u);
  EXPECT_EQ(labels[g.index(8, 1, 0)], labels[g.index(10, 1, 0)]);
  EXPECT_EQ(largest_component(mask)(10, 1, 0), 1);
  EXPECT_EQ(largest_component(mask)(1, 1, 0), 0);
}

}  // namespace
}  // namespace facehex
