#include "core/segment/slice_shear.h"

#include <gtest/gtest.h>

#include <cmath>

namespace facehex {
namespace {

// Slices of a field linear in position (3 x + 5 y + 7 z, mm), each sampled on its own window moved by a fraction of
// a pixel: bilinear interpolation reproduces a linear field, so the upright volume holds it exactly where a slice
// reaches, and the fill elsewhere.
TEST(SliceShear, ALinearFieldSampledOnMovedWindowsIsUprightAgain) {
  GridGeometry g;
  g.dims = {6, 5, 4};
  g.spacing = Eigen::Vector3d(0.5, 0.8, 2.0);
  g.origin = Eigen::Vector3d(10, 20, 30);
  const std::vector<Eigen::Vector2d> offsets = {{0, 0}, {0.2, -0.3}, {-0.35, -0.6}, {0.1, -1.0}};
  const auto linear = [](const Eigen::Vector3d& p) { return 3 * p.x() + 5 * p.y() + 7 * p.z(); };
  Field stacked(g, 0.0f);
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 6; ++i) {
        Eigen::Vector3d p = g.point(i, j, k);
        p.head<2>() += offsets[k];
        stacked(i, j, k) = static_cast<float>(linear(p));
      }
  constexpr float kFill = -3024;
  const Field upright = unshear_slices(stacked, offsets, kFill);
  const GridGeometry& u = upright.geometry;
  // The union of the windows: x from -0.35 to 2.7 mm past the origin, y from -1.0 to 3.2.
  EXPECT_TRUE(u.origin.isApprox(Eigen::Vector3d(9.65, 19.0, 30))) << u.origin.transpose();
  EXPECT_EQ(u.dims, (std::array<int, 3>{8, 7, 4}));  // whole pixels reaching past both ends
  int reached = 0, filled = 0;
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < u.dims[1]; ++j)
      for (int i = 0; i < u.dims[0]; ++i) {
        const Eigen::Vector3d p = u.point(i, j, k);
        const Eigen::Vector2d in_window =
            (p.head<2>() - g.origin.head<2>() - offsets[k]).cwiseQuotient(g.spacing.head<2>());
        const bool inside = in_window.minCoeff() > -1e-9 && in_window.x() < 5 + 1e-9 && in_window.y() < 4 + 1e-9;
        if (inside) {
          EXPECT_NEAR(upright(i, j, k), linear(p), 1e-3) << i << " " << j << " " << k;
          ++reached;
        } else {
          EXPECT_EQ(upright(i, j, k), kFill) << i << " " << j << " " << k;
          ++filled;
        }
      }
  EXPECT_GT(reached, 0);
  EXPECT_GT(filled, 0);
}

}  // namespace
}  // namespace facehex
