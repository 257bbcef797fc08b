#include "core/segment/side_labels.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>
#include <vector>

namespace facehex {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The cuts of these tests: top z = 100, bottom z = 0, posterior y = 0, mid-plane x = 50, jaw cut y + z = 30.
FaceCuts cuts(bool jaw = true) {
  FaceCuts c;
  c.top_z = 100;
  c.bottom_z = 0;
  c.posterior_y = 0;
  c.centre_x = 50;
  if (jaw) c.jaw_z = 30;
  return c;
}

// Distance fields over [-10, 110]^3 (5 mm voxels): air in front (air_distance = 100 - y), the tissue not in the model
// behind (inner_distance = y). Both are linear, so trilinear sampling is exact: a face is skin (w1) iff its centroid
// has y >= 50.
struct Distances {
  Field air, inner;
  Distances() {
    GridGeometry g;
    g.dims = {25, 25, 25};
    g.spacing = Eigen::Vector3d::Constant(5);
    g.origin = Eigen::Vector3d::Constant(-10);
    air = Field(g, 0);
    inner = Field(g, 0);
    for (int k = 0; k < 25; ++k)
      for (int j = 0; j < 25; ++j)
        for (int i = 0; i < 25; ++i) {
          const double y = g.point(i, j, k).y();
          air(i, j, k) = static_cast<float>(100 - y);
          inner(i, j, k) = static_cast<float>(y);
        }
  }
};

// Separate triangles, each with the given centroid and (unit) right-hand normal, about 2 mm across.
struct Faces {
  SurfaceMesh surface;
  void add(const Eigen::Vector3d& centroid, const Eigen::Vector3d& normal) {
    const Eigen::Vector3d n = normal.normalized();
    const Eigen::Vector3d t1 = n.unitOrthogonal(), t2 = n.cross(t1);  // t1 x t2 = n
    const int first = static_cast<int>(surface.V.rows());
    surface.V.conservativeResize(first + 3, 3);
    for (int k = 0; k < 3; ++k) {
      const double a = 2 * kPi * k / 3;  // counter-clockwise about n
      surface.V.row(first + k) = (centroid + std::cos(a) * t1 + std::sin(a) * t2).transpose();
    }
    surface.F.conservativeResize(surface.F.rows() + 1, 3);
    surface.F.row(surface.F.rows() - 1) << first, first + 1, first + 2;
  }
};

Eigen::Vector3d tilted_z(double degrees, double sign = 1) {  // +z (or -z) tilted towards +y
  const double a = degrees * kPi / 180;
  return {0, std::sin(a), sign * std::cos(a)};
}

TEST(ClassifySides, EachCutPlaneGivesItsSideAndTheRestIsSkinOrBone) {
  const Distances d;
  Faces f;
  std::vector<int> expected;
  const auto add = [&](const Eigen::Vector3d& c, const Eigen::Vector3d& n, Side side) {
    f.add(c, n);
    expected.push_back(side);
  };
  add({50, 40, 100}, {0, 0, 1}, V1);                  // on the top cut
  add({50, 40, 100}, tilted_z(40), V1);               // facing out of it within 45 degrees
  add({50, 70, 100}, tilted_z(50), W1);               // too steep for the top cut: skin (y >= 50)
  add({50, 30, 100}, tilted_z(50), W0);               // ... or bone (y < 50)
  add({50, 30, 100}, {0, 0, -1}, W0);                 // on the top plane facing into the model
  add({50, 60, 0}, {0, 0, -1}, V0);                   // on the bottom cut
  add({30, 0, 50}, {0, -1, 0}, U0);                   // on the posterior cut at x < 50
  add({70, 0, 50}, {0, -1, 0}, U1);                   // ... and at x > 50
  add({49, 0, 60}, {0, -1, 0}, U0);                   // just either side of the mid-plane
  add({51, 0, 60}, {0, -1, 0}, U1);                   //
  add({50, 10, 20}, Eigen::Vector3d(0, -1, -1), V0);  // on the jaw cut (y + z = 30)
  add({50, 80, 50}, {0, 1, 0}, W1);                   // the front of the face: skin
  add({50, 20, 50}, {0, 1, 0}, W0);                   // inside, nearer the tissue behind: bone
  add({20, 52, 50}, {-1, 0, 0}, W1);                  // a side face, 2 mm nearer the air
  add({80, 47, 50}, {1, 0, 0}, W0);                   // a side face, 3 mm nearer the tissue behind
  const Eigen::VectorXi sides = classify_sides(f.surface, cuts(), d.air, d.inner, 0.5);
  ASSERT_EQ(sides.size(), static_cast<int>(expected.size()));
  for (int i = 0; i < sides.size(); ++i) EXPECT_EQ(sides(i), expected[i]) << "face " << i;
}

TEST(ClassifySides, OnAPlaneMeansWithinThePlaneTolerance) {
  const Distances d;
  Faces f;
  f.add({50, 40, 100.4}, {0, 0, 1});  // 0.4 mm above the top cut
  f.add({50, 40, 99.4}, {0, 0, 1});   // 0.6 mm below it
  f.add({30, -0.2, 50}, {0, -1, 0});  // 0.2 mm behind the posterior cut
  Eigen::VectorXi sides = classify_sides(f.surface, cuts(), d.air, d.inner, 0.5);
  EXPECT_EQ(sides(0), V1);
  EXPECT_EQ(sides(1), W0);
  EXPECT_EQ(sides(2), U0);
  sides = classify_sides(f.surface, cuts(), d.air, d.inner, 0.7);
  EXPECT_EQ(sides(1), V1);
  sides = classify_sides(f.surface, cuts(), d.air, d.inner, 0.1);
  EXPECT_EQ(sides(0), W0);
  EXPECT_EQ(sides(2), W0);
}

TEST(ClassifySides, NoJawCutWithoutJawZ) {
  const Distances d;
  Faces f;
  f.add({50, 10, 20}, Eigen::Vector3d(0, -1, -1));
  EXPECT_EQ(classify_sides(f.surface, cuts(true), d.air, d.inner, 0.5)(0), V0);
  EXPECT_EQ(classify_sides(f.surface, cuts(false), d.air, d.inner, 0.5)(0), W0);
}

// A flat strip of n x m unit squares, each split into two triangles; faces 2 (i + n j) and 2 (i + n j) + 1 make
// square (i, j).
Eigen::MatrixXi strip(int n, int m) {
  Eigen::MatrixXi F(2 * n * m, 3);
  auto v = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const int s = i + n * j;
      F.row(2 * s) << v(i, j), v(i + 1, j), v(i + 1, j + 1);
      F.row(2 * s + 1) << v(i, j), v(i + 1, j + 1), v(i, j + 1);
    }
  return F;
}

// Sets both triangles of the squares (i, j) with i0 <= i < i1, j0 <= j < j1.
void paint(Eigen::VectorXi& sides, int n, int i0, int i1, int j0, int j1, Side side) {
  for (int j = j0; j < j1; ++j)
    for (int i = i0; i < i1; ++i) sides(2 * (i + n * j)) = sides(2 * (i + n * j) + 1) = side;
}

TEST(SideIslands, CountPatchesCountsEdgeConnectedPieces) {
  const int n = 10, m = 6;
  const Eigen::MatrixXi F = strip(n, m);
  Eigen::VectorXi sides = Eigen::VectorXi::Constant(F.rows(), W1);
  EXPECT_EQ(count_patches(F, sides, -1), 1);
  EXPECT_EQ(count_patches(F, sides, W1), 1);
  EXPECT_EQ(count_patches(F, sides, V0), 0);
  paint(sides, n, 0, n, 2, 3, V0);  // a row across the strip cuts W1 in two
  EXPECT_EQ(count_patches(F, sides, W1), 2);
  EXPECT_EQ(count_patches(F, sides, V0), 1);
  paint(sides, n, 5, 6, 4, 5, U0);  // two separate single squares
  paint(sides, n, 8, 9, 5, 6, U0);
  EXPECT_EQ(count_patches(F, sides, U0), 2);
  EXPECT_EQ(count_patches(F, sides, -1), 1);  // all faces: still one piece
  // Triangles meeting at a vertex only are two patches.
  Eigen::MatrixXi corner(2, 3);
  corner << 0, 1, 2, 2, 3, 4;
  EXPECT_EQ(count_patches(corner, Eigen::VectorXi::Zero(2), -1), 2);
}

TEST(SideIslands, SpecksTakeTheSideAroundThem) {
  const int n = 12, m = 8;
  const Eigen::MatrixXi F = strip(n, m);
  Eigen::VectorXi sides(F.rows());
  paint(sides, n, 0, 6, 0, m, W1);   // left half skin
  paint(sides, n, 6, n, 0, m, V0);   // right half bottom cut
  paint(sides, n, 2, 3, 3, 4, V0);   // a speck of v0 inside the skin
  paint(sides, n, 9, 10, 5, 6, W1);  // a speck of skin inside v0
  paint(sides, n, 1, 4, 5, 8, U1);   // a patch of u1, u1's only one: kept though small
  sides(2 * (8 + n * 1)) = W0;       // a single triangle of w0, alone: kept
  Eigen::VectorXi expected = sides;
  paint(expected, n, 2, 3, 3, 4, W1);
  paint(expected, n, 9, 10, 5, 6, V0);
  EXPECT_EQ(count_patches(F, sides, V0), 2);
  EXPECT_EQ(count_patches(F, sides, W1), 2);
  merge_side_islands(F, sides);
  EXPECT_EQ(sides, expected);
  for (Side s : {W1, V0, U1, W0}) EXPECT_EQ(count_patches(F, sides, s), 1) << kSideNames[s];
}

TEST(SideIslands, ALargeIslandIsFilledRingByRing) {
  const int n = 16, m = 16;
  const Eigen::MatrixXi F = strip(n, m);
  Eigen::VectorXi sides = Eigen::VectorXi::Constant(F.rows(), W1);
  paint(sides, n, 0, n, 12, m, W0);  // the main w0 patch: 64 squares
  paint(sides, n, 3, 9, 2, 8, W0);   // an island of w0 in the skin, 6 x 6 squares: needs several rings
  EXPECT_EQ(count_patches(F, sides, W0), 2);
  merge_side_islands(F, sides);
  Eigen::VectorXi expected = Eigen::VectorXi::Constant(F.rows(), W1);
  paint(expected, n, 0, n, 12, m, W0);
  EXPECT_EQ(sides, expected);
}

TEST(SideIslands, AnIslandBetweenTwoSidesTakesTheMostCommonNeighbour) {
  // One triangle of u0 (an island: u0's main patch is elsewhere), the first of square (6, 2): its three edges meet
  // square (6, 1) below, square (7, 2) on the right and the other triangle of its own square.
  const int n = 9, m = 5, island = 2 * (6 + n * 2);
  const Eigen::MatrixXi F = strip(n, m);
  Eigen::VectorXi sides = Eigen::VectorXi::Constant(F.rows(), W1);
  paint(sides, n, 0, 2, 0, m, U0);  // u0's main patch
  paint(sides, n, 5, n, 0, 2, V1);  // v1 along the bottom right
  sides(island) = U0;
  Eigen::VectorXi merged = sides;
  merge_side_islands(F, merged);
  EXPECT_EQ(merged(island), W1);  // v1 below, w1 on two edges
  merged(island) = U0;
  EXPECT_EQ(merged, sides);  // nothing else changed

  paint(sides, n, 7, 8, 2, 3, V1);  // now v1 on the right too
  merge_side_islands(F, sides);
  EXPECT_EQ(sides(island), V1);  // v1 on two edges, w1 on one
}

TEST(SideIslands, NothingChangesWithoutIslands) {
  const int n = 8, m = 4;
  const Eigen::MatrixXi F = strip(n, m);
  Eigen::VectorXi sides(F.rows());
  paint(sides, n, 0, 4, 0, m, W0);
  paint(sides, n, 4, n, 0, m, W1);
  const Eigen::VectorXi before = sides;
  merge_side_islands(F, sides);
  EXPECT_EQ(sides, before);
}

}  // namespace
}  // namespace facehex
