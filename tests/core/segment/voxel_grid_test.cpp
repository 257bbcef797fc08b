// The Gaussian blur of a voxel field against a direct evaluation of its definition (each voxel the kernel-weighted sum
// of its neighbours along one axis after the other, the border value beyond the grid): the same floats, bit for bit,
// on a random field with a different spacing per axis; a constant field stays constant; the kernel is a normalized
// Gaussian reaching 3 sigma.
#include "core/segment/voxel_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace facehex {
namespace {

Field direct_gaussian(const Field& field, double sigma) {
  Field out = field;
  const GridGeometry& g = field.geometry;
  for (int axis = 0; axis < 3; ++axis) {
    const std::vector<double> kernel = gaussian_kernel(sigma / g.spacing(axis));
    const int r = static_cast<int>(kernel.size() / 2);
    const Field in = out;
    for (int k = 0; k < g.dims[2]; ++k)
      for (int j = 0; j < g.dims[1]; ++j)
        for (int i = 0; i < g.dims[0]; ++i) {
          int at[3] = {i, j, k};
          const int x = at[axis];
          double sum = 0;
          for (int d = -r; d <= r; ++d) {
            at[axis] = std::clamp(x + d, 0, g.dims[axis] - 1);
            sum += kernel[d + r] * in(at[0], at[1], at[2]);
          }
          out(i, j, k) = static_cast<float>(sum);
        }
  }
  return out;
}

TEST(VoxelGrid, GaussianSmoothIsItsDefinitionBitForBit) {
  GridGeometry g;
  g.dims = {19, 14, 9};
  g.spacing = Eigen::Vector3d(0.7, 1.0, 2.5);
  Field f(g, 0.0f);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> value(-1000.0f, 1500.0f);
  for (float& v : f.data) v = value(random);
  for (const double sigma : {0.5, 1.3, 4.0}) {  // 4 mm: kernels longer than the grid along x and y
    const Field blurred = gaussian_smooth(f, sigma), expected = direct_gaussian(f, sigma);
    EXPECT_TRUE(blurred.data == expected.data) << "sigma " << sigma;
  }
  const Field flat = gaussian_smooth(Field(g, 42.0f), 1.3);
  const std::vector<double> kernel = gaussian_kernel(1.5);  // 1.5 voxels: taps -5 .. 5
  ASSERT_EQ(kernel.size(), 11u);
  double total = 0;
  for (const double w : kernel) total += w;
  EXPECT_NEAR(total, 1.0, 1e-15);
  EXPECT_NEAR(kernel[6] / kernel[5], std::exp(-0.5 / (1.5 * 1.5)), 1e-15);
  EXPECT_EQ(kernel[4], kernel[6]);
  for (const float v : flat.data) EXPECT_NEAR(v, 42.0f, 1e-4f);
}

}  // namespace
}  // namespace facehex
