#include "core/standard/closed_domain.h"

#include <gtest/gtest.h>

#include <functional>

#include "core/mesh/sides.h"
#include "core/mesh/tet_laplacian.h"
#include "core/mesh/tet_topology.h"
#include "tests/core/test_meshes.h"

namespace facehex {
namespace {

constexpr int kNx = 5, kNy = 3, kNz = 5;  // cells of the 10 x 6 x 10 mm box

// The 10 x 6 x 10 mm box without the cells `removed` picks (test::tet_box_without).
VolumeMesh box_without(const std::function<bool(int, int, int)>& removed) {
  return test::tet_box_without(kNx, kNy, kNz, 10, 6, 10, removed);
}

TEST(CloseOpenings, ATunnelThroughTheShellGetsAPlugThatFillsIt) {
  // A 2 x 2 mm square tunnel from the back to the front through the middle of the box.
  const VolumeMesh model = box_without([](int i, int, int k) { return i == 2 && k == 2; });
  const TetDomain open = own_domain(model);
  const TetDomain closed = close_openings(open, "the model's own tets");
  EXPECT_EQ(closed.closed_openings, 1);
  EXPECT_EQ(closed.description, "the model's own tets with 1 of 1 openings closed by TetGen plugs");
  ASSERT_GT(closed.T.rows(), open.T.rows());
  // The model's vertices and tets come first, unchanged; the plug fills exactly the tunnel's 2 x 6 x 2 mm.
  EXPECT_EQ(closed.V.topRows(open.V.rows()), open.V);
  EXPECT_EQ(closed.T.topRows(open.T.rows()), open.T);
  EXPECT_EQ(closed.hex_vertices, open.hex_vertices);
  const Eigen::VectorXd volumes = tet_volumes(closed.V, closed.T);
  EXPECT_NEAR(volumes.sum(), 10.0 * 6.0 * 10.0, 1e-9);
  EXPECT_GT(volumes.minCoeff(), 0);
  for (Eigen::Index v = open.V.rows(); v < closed.V.rows(); ++v) EXPECT_EQ(closed.side_mask(v), 0);
  // The closed model's boundary is the box's: every boundary face lies on a side.
  const BoundaryFaces boundary = boundary_faces(closed.T);
  for (Eigen::Index f = 0; f < boundary.F.rows(); ++f)
    EXPECT_NE(
        closed.side_mask(boundary.F(f, 0)) & closed.side_mask(boundary.F(f, 1)) & closed.side_mask(boundary.F(f, 2)), 0)
        << "face " << f;
}

TEST(CloseOpenings, ADentInOneSideAndMeetingSidesAreNoOpenings) {
  // A 2 x 2 mm pocket in the front, one cell deep: its rim is one loop on the front.
  const VolumeMesh dented = box_without([](int i, int j, int k) { return i == 2 && k == 2 && j == kNy - 1; });
  const TetDomain dent = close_openings(own_domain(dented), "the model's own tets");
  EXPECT_EQ(dent.closed_openings, 0);
  EXPECT_EQ(dent.T.rows(), own_domain(dented).T.rows());
  EXPECT_EQ(dent.description, "the model's own tets, no opening");
  // The whole box: its edges and corners carry two or three sides, its faces one; nothing to close.
  const VolumeMesh box = box_without([](int, int, int) { return false; });
  EXPECT_EQ(close_openings(own_domain(box), "the model's own tets").T.rows(), own_domain(box).T.rows());
}

TEST(CloseOpenings, AModelWithoutSideLabelsIsLeftAsItIs) {
  VolumeMesh model = box_without([](int i, int, int k) { return i == 2 && k == 2; });
  model.point_data.clear();
  const TetDomain d = close_openings(own_domain(model), "the model's own tets");
  EXPECT_EQ(d.closed_openings, 0);
  EXPECT_EQ(d.T.rows(), model.num_cells());
}

}  // namespace
}  // namespace facehex
