#include "core/untangle.h"

#include "core/corner_jacobian.h"
#include "test_meshes.h"

#include <gtest/gtest.h>

namespace facehex {
namespace {

std::vector<char> boundary_fixed(const VolumeMesh& m) {
  const Eigen::MatrixXd& mask = m.point_data.at(kSideMaskArray);
  std::vector<char> fixed(m.num_vertices());
  for (int v = 0; v < m.num_vertices(); ++v) fixed[v] = mask(v) != 0;
  return fixed;
}

TEST(Untangle, RepairsADeliberatelyInvertedMeshWithoutMovingTheBoundary) {
  VolumeMesh m = test::hex_box(4, 4, 4, 4, 4, 4);
  const Eigen::MatrixXd boundary_before = m.V;
  // Push the interior vertex at (2,2,2) through two cells and drag a neighbour the other way.
  const int centre = (2 * 5 + 2) * 5 + 2, neighbour = (2 * 5 + 2) * 5 + 3;
  m.V.row(centre) += Eigen::RowVector3d(1.6, 0.3, -0.2);
  m.V.row(neighbour) += Eigen::RowVector3d(-1.5, 0.0, 0.4);
  const int inverted_before = static_cast<int>(check_corner_jacobians(m).inverted.size());
  ASSERT_GT(inverted_before, 0);
  const std::vector<char> fixed = boundary_fixed(m);
  VertexPlacement placement = spatial_placement(m.V, fixed);
  const UntangleReport r = untangle(m, placement);
  EXPECT_EQ(r.inverted_before, inverted_before);
  EXPECT_EQ(r.inverted_after, 0);
  EXPECT_TRUE(check_corner_jacobians(m).inverted.empty());
  EXPECT_GT(r.min_scaled_jacobian_after, 0.2);
  for (int v = 0; v < m.num_vertices(); ++v)
    if (fixed[v]) {
      EXPECT_EQ((m.V.row(v) - boundary_before.row(v)).norm(), 0.0) << v;
    }
}

TEST(Untangle, RepairsAFlatCellThatIsNotInverted) {
  VolumeMesh m = test::hex_box(3, 3, 3, 3, 3, 3);
  // Interior vertex (1,1,1) moved almost onto the midpoint of two of its neighbours: positive but ~0 Jacobians.
  auto id = [](int i, int j, int k) { return (k * 4 + j) * 4 + i; };
  const double t = 1 - 1e-9;
  m.V.row(id(1, 1, 1)) = (1 - t) * m.V.row(id(1, 1, 1)) + t * 0.5 * (m.V.row(id(2, 1, 1)) + m.V.row(id(1, 2, 1)));
  const CornerJacobianCheck before = check_corner_jacobians(m);
  ASSERT_TRUE(before.inverted.empty());
  ASSERT_FALSE(before.degenerate.empty());
  VertexPlacement placement = spatial_placement(m.V, boundary_fixed(m));
  const UntangleReport r = untangle(m, placement);
  EXPECT_EQ(r.degenerate_before, static_cast<int>(before.degenerate.size()));
  EXPECT_EQ(r.degenerate_after, 0);
  EXPECT_EQ(r.inverted_after, 0);
  EXPECT_TRUE(check_corner_jacobians(m).unusable().empty());
  EXPECT_GT(r.min_scaled_jacobian_after, 0.2);
}

TEST(Untangle, LeavesAGoodMeshUntouched) {
  VolumeMesh m = test::hex_box(3, 3, 3);
  test::jitter_interior(m, 0.05);
  const Eigen::MatrixXd before = m.V;
  VertexPlacement placement = spatial_placement(m.V, boundary_fixed(m));
  const UntangleReport r = untangle(m, placement);
  EXPECT_EQ(r.bad_before, 0);
  EXPECT_EQ(m.V, before);
}

}  // namespace
}  // namespace facehex
