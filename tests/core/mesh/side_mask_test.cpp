#include "core/mesh/side_mask.h"

#include <gtest/gtest.h>

#include "core/fields/constraint_set.h"
#include "core/mesh/sides.h"
#include "tests/core/test_meshes.h"

namespace facehex {
namespace {

TEST(RelaxCornerQuads, LeavesAWellLabelledBoxAlone) {
  const VolumeMesh box = test::hex_box(3, 2, 2);
  Eigen::VectorXi mask = side_mask_of(box);
  const Eigen::VectorXi before = mask;
  EXPECT_EQ(relax_corner_quads(box, mask), 0);
  EXPECT_EQ(mask, before);
}

TEST(RelaxCornerQuads, TheMiddleOfThreeEdgeVerticesOfOneFaceKeepsOnlyTheFacesSide) {
  // A unit cube whose face x = 1 (nodes 1, 3, 7, 5 going round) lies on u1, with three of its four vertices also
  // claiming v0, as a hand-built shell's corner can be labelled: pinned to the u1-v0 edge line, the face would be flat.
  const VolumeMesh cube = test::hex_box(1, 1, 1);
  Eigen::VectorXi mask = Eigen::VectorXi::Zero(cube.num_vertices());
  for (int v : {1, 3, 7, 5}) mask(v) = side_bit(U1);
  for (int v : {3, 1, 5}) mask(v) |= side_bit(V0);
  EXPECT_EQ(relax_corner_quads(cube, mask), 1);
  EXPECT_EQ(mask(1), side_bit(U1));  // the middle one keeps the face's side only
  EXPECT_EQ(mask(3), side_bit(U1) | side_bit(V0));
  EXPECT_EQ(mask(5), side_bit(U1) | side_bit(V0));
  EXPECT_EQ(mask(7), side_bit(U1));
  EXPECT_EQ(relax_corner_quads(cube, mask), 0);  // nothing left to relax
}

}  // namespace
}  // namespace facehex
