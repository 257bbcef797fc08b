#include "core/mesh/shell_sides.h"

#include <gtest/gtest.h>

#include <set>
#include <utility>

#include "core/fields/constraint_set.h"
#include "core/mesh/sides.h"
#include "tests/core/test_meshes.h"

namespace facehex {
namespace {

using test::hex_box_vertex;

// A flat shell of nx x nz columns of unit hexes, `layers` cells thick along y (test_meshes.h hex_box: the skin at the
// front, +z up), without the columns (i, k) in `holes` (openings through it).
VolumeMesh slab(int nx, int layers, int nz, const std::set<std::pair<int, int>>& holes = {}) {
  return test::hex_box_without(nx, layers, nz, nx, layers, nz, [&](int i, int, int k) {
    return holes.count({i, k}) > 0;
  });
}

TEST(ShellSides, AFlatShellHasItsSkinInFrontAndItsCutsAround) {
  const VolumeMesh m = slab(8, 2, 8);
  const ShellSides sides = label_shell_sides(m, default_shell_frame(m.V));
  EXPECT_EQ(sides.layers, 2);
  EXPECT_EQ(sides.faces_per_side[W1], 64);
  EXPECT_EQ(sides.faces_per_side[W0], 64);
  EXPECT_EQ(sides.faces_per_side[V1], 16);  // the rim at the top: 8 columns x 2 layers
  EXPECT_EQ(sides.faces_per_side[U0], 16);
  EXPECT_EQ(sides.opening_faces, 0);
  EXPECT_TRUE(sides.side_mask == side_mask_of(m));  // the box's own sides, corners and creases included
}

// Two openings side by side, with a pillar between them as thick (in cells) as the shell: the chords across the
// pillar have the shell's length, but its walls are the openings', not a patch of skin and bone (a nose's columella
// between the nostrils).
TEST(ShellSides, APillarBetweenTwoOpeningsIsPartOfTheirWalls) {
  std::set<std::pair<int, int>> holes;
  for (int k = 3; k <= 6; ++k) {
    holes.insert({3, k});
    holes.insert({6, k});
  }
  const VolumeMesh m = slab(10, 2, 10, holes);
  const ShellSides sides = label_shell_sides(m, default_shell_frame(m.V));
  EXPECT_EQ(sides.layers, 2);
  EXPECT_EQ(sides.faces_per_side[W1], 92);
  EXPECT_EQ(sides.faces_per_side[W0], 92);
  EXPECT_EQ(sides.opening_faces, 2 * 2 * (2 * (1 + 4)));  // two openings, a wall of 1 x 4 columns, 2 layers each
  // The pillar's walls are on no side between the skin and the bone.
  for (int k = 4; k <= 6; ++k) {
    EXPECT_EQ(sides.side_mask(hex_box_vertex(10, 2, 4, 1, k)), 0) << k;
    EXPECT_EQ(sides.side_mask(hex_box_vertex(10, 2, 6, 1, k)), 0) << k;
  }
  EXPECT_EQ(sides.side_mask(hex_box_vertex(10, 2, 5, 2, 5)), side_bit(W1));
  EXPECT_EQ(sides.conflicting_vertices, 0);
}

}  // namespace
}  // namespace facehex
