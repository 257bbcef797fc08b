#include "core/mesh/shell_sides.h"

#include <gtest/gtest.h>

#include <set>
#include <utility>

#include "core/mesh/sides.h"

namespace facehex {
namespace {

// A flat shell of nx x ny columns of hexes, `layers` cells thick along z (the skin on top), without the columns in
// `holes` (openings through it). The frame's centre lies below it, +y is up and +x lateral.
struct Slab {
  VolumeMesh mesh;
  ShellFrame frame;
  int nx, ny, layers;
  int vertex(int i, int j, int k) const { return (k * (ny + 1) + j) * (nx + 1) + i; }
};

Slab slab(int nx, int ny, int layers, const std::set<std::pair<int, int>>& holes) {
  Slab s{{}, {}, nx, ny, layers};
  s.mesh.V.resize((nx + 1) * (ny + 1) * (layers + 1), 3);
  for (int k = 0; k <= layers; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) s.mesh.V.row(s.vertex(i, j, k)) << i, j, k;
  std::vector<Eigen::Matrix<int, 1, 8>> cells;
  for (int k = 0; k < layers; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (holes.count({i, j})) continue;
        Eigen::Matrix<int, 1, 8> c;
        c << s.vertex(i, j, k), s.vertex(i + 1, j, k), s.vertex(i + 1, j + 1, k), s.vertex(i, j + 1, k),
            s.vertex(i, j, k + 1), s.vertex(i + 1, j, k + 1), s.vertex(i + 1, j + 1, k + 1), s.vertex(i, j + 1, k + 1);
        cells.push_back(c);
      }
  s.mesh.C.resize(static_cast<Eigen::Index>(cells.size()), 8);
  for (size_t c = 0; c < cells.size(); ++c) s.mesh.C.row(static_cast<Eigen::Index>(c)) = cells[c];
  s.mesh.types.assign(cells.size(), CellType::Hex);
  s.frame.center = Eigen::Vector3d(0.5 * nx, 0.5 * ny, -100);
  s.frame.up = Eigen::Vector3d::UnitY();
  return s;
}

TEST(ShellSides, AFlatShellHasItsSkinOnTopAndItsCutsAround) {
  const Slab s = slab(8, 8, 2, {});
  const ShellSides sides = label_shell_sides(s.mesh, s.frame);
  EXPECT_EQ(sides.layers, 2);
  EXPECT_EQ(sides.faces_per_side[W1], 64);
  EXPECT_EQ(sides.faces_per_side[W0], 64);
  EXPECT_EQ(sides.faces_per_side[V1], 16);  // the rim at +y: 8 columns x 2 layers
  EXPECT_EQ(sides.faces_per_side[U0], 16);
  EXPECT_EQ(sides.opening_faces, 0);
  EXPECT_EQ(sides.side_mask(s.vertex(3, 3, 2)), side_bit(W1));
  EXPECT_EQ(sides.side_mask(s.vertex(3, 3, 0)), side_bit(W0));
}

// Two openings side by side, with a pillar between them as thick (in cells) as the shell: the chords across the
// pillar have the shell's length, but its walls are the openings', not a patch of skin and bone (a nose's columella
// between the nostrils).
TEST(ShellSides, APillarBetweenTwoOpeningsIsPartOfTheirWalls) {
  std::set<std::pair<int, int>> holes;
  for (int j = 3; j <= 6; ++j) {
    holes.insert({3, j});
    holes.insert({6, j});
  }
  const Slab s = slab(10, 10, 2, holes);
  const ShellSides sides = label_shell_sides(s.mesh, s.frame);
  EXPECT_EQ(sides.layers, 2);
  EXPECT_EQ(sides.faces_per_side[W1], 92);
  EXPECT_EQ(sides.faces_per_side[W0], 92);
  EXPECT_EQ(sides.opening_faces, 2 * 2 * (2 * (1 + 4)));  // two openings, a wall of 1 x 4 columns, 2 layers each
  // The pillar's walls are on no side between the skin and the bone.
  for (int j = 4; j <= 6; ++j) {
    EXPECT_EQ(sides.side_mask(s.vertex(4, j, 1)), 0) << j;
    EXPECT_EQ(sides.side_mask(s.vertex(6, j, 1)), 0) << j;
  }
  EXPECT_EQ(sides.side_mask(s.vertex(5, 5, 2)), side_bit(W1));
  EXPECT_EQ(sides.conflicting_vertices, 0);
}

}  // namespace
}  // namespace facehex
