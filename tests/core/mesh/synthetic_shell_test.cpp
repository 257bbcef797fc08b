#include "core/mesh/synthetic_shell.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <map>
#include <set>

#include "core/mesh/sides.h"

namespace facehex {
namespace {

TEST(SyntheticShell, IsAClosedOutwardSurfaceWithAllSixSides) {
  const SurfaceMesh s = synthetic_shell_surface();
  // Closed and consistently oriented: every directed edge appears once and its reverse once.
  std::map<std::pair<int, int>, int> directed;
  for (int f = 0; f < s.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++directed[{s.F(f, k), s.F(f, (k + 1) % 3)}];
  for (const auto& [e, n] : directed) {
    EXPECT_EQ(n, 1);
    EXPECT_EQ(directed.count({e.second, e.first}), 1u);
  }
  // Outward: the enclosed volume (divergence theorem) is positive and close to the shell's analytic volume.
  double volume = 0;
  for (int f = 0; f < s.F.rows(); ++f)
    volume += Eigen::Vector3d(s.V.row(s.F(f, 0)))
                  .dot(Eigen::Vector3d(s.V.row(s.F(f, 1))).cross(Eigen::Vector3d(s.V.row(s.F(f, 2))))) /
              6;
  const SyntheticShellOptions o;
  const double ring =
      0.5 * 2 * o.t_max * ((o.inner_a + o.thickness) * (o.inner_b + o.thickness) - o.inner_a * o.inner_b);
  EXPECT_GT(volume, 0.9 * ring * (o.z_max - o.z_min));  // plus the nose bump
  EXPECT_LT(volume, 1.3 * ring * (o.z_max - o.z_min));
  const std::set<int> labels(s.labels.data(), s.labels.data() + s.labels.size());
  EXPECT_EQ(labels, (std::set<int>{U0 + 1, U1 + 1, V0 + 1, V1 + 1, W0 + 1, W1 + 1}));
}

}  // namespace
}  // namespace facehex
