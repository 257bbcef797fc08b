#include "core/io/mesh_io.h"
#include "io_test_util.h"

#include <gtest/gtest.h>

namespace facehex {
namespace {

using test::TempDir;
namespace fs = std::filesystem;

// Closed octahedron, outward oriented, labelled by hemisphere.
SurfaceMesh octahedron() {
  SurfaceMesh s;
  s.V.resize(6, 3);
  s.V << 10, 0, 0, -10, 0, 0, 0, 10, 0, 0, -10, 0, 0, 0, 10, 0, 0, -10;
  s.F.resize(8, 3);
  s.F << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  s.labels.resize(8);
  s.labels << 1, 1, 1, 1, 2, 2, 2, 2;
  return s;
}

class SurfaceRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(SurfaceRoundTrip, KeepsPointsAndTriangles) {
  TempDir dir;
  const SurfaceMesh s = octahedron();
  const std::string path = dir.file("octa" + GetParam());
  write_surface_mesh(path, s);
  const SurfaceMesh back = read_surface_mesh(path);
  ASSERT_EQ(back.V.rows(), 6) << "per-triangle copies (STL) must be merged";
  ASSERT_EQ(back.F.rows(), 8);
  // Points may be renumbered by merging: compare triangles by their coordinates, orientation included.
  for (int f = 0; f < 8; ++f) {
    bool found = false;
    for (int g = 0; g < 8 && !found; ++g)
      for (int r = 0; r < 3 && !found; ++r) {
        bool same = true;
        for (int k = 0; k < 3; ++k)
          same = same && (back.V.row(back.F(g, (k + r) % 3)) - s.V.row(s.F(f, k))).norm() < 1e-5;
        found = same;
      }
    EXPECT_TRUE(found) << "triangle " << f << " lost or flipped";
  }
  if (GetParam() == ".vtp") {
    EXPECT_EQ(back.labels, s.labels);
  }
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"octa" + GetParam()});
}

INSTANTIATE_TEST_SUITE_P(Formats, SurfaceRoundTrip, ::testing::Values(".vtp", ".stl", ".ply", ".obj"));

TEST(SurfaceIo, QuadsAreTriangulated) {
  TempDir dir;
  const std::string path = dir.file("quads.obj");
  test::write_file(path, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 0\nf 1 2 3 4\nf 5 3 2\n");
  const SurfaceMesh s = read_surface_mesh(path);
  EXPECT_EQ(s.F.rows(), 3);
  EXPECT_EQ(s.V.rows(), 4) << "the duplicate of point 1 is merged";
}

TEST(SurfaceIo, InvalidSurfaceIsNotWritten) {
  TempDir dir;
  SurfaceMesh s = octahedron();
  s.F(3, 1) = 6;
  test::expect_error([&] { write_surface_mesh(dir.file("bad.stl"), s); }, "bad.stl: triangle refers to a point");
  s = octahedron();
  s.labels.resize(3);
  test::expect_error([&] { write_surface_mesh(dir.file("bad.vtp"), s); }, "3 labels for 8 triangles");
  test::expect_error([&] { write_surface_mesh(dir.file("octa.vtu"), octahedron()); }, "cannot write surfaces");
  test::expect_error([&] { write_surface_mesh(dir.file("no/octa.stl"), octahedron()); }, "does not exist");
  EXPECT_TRUE(dir.entries().empty());
}

TEST(SurfaceIo, VolumeReadOfASurfaceTetrahedralizes) {
  TempDir dir;
  write_surface_mesh(dir.file("octa.stl"), octahedron());
  MeshReadOptions options;
  options.target_edge_length = 5.0;
  const VolumeMesh m = read_volume_mesh(dir.file("octa.stl"), options);
  ASSERT_TRUE(m.is_tet_mesh());
  double volume = 0;
  for (int c = 0; c < m.num_cells(); ++c) {
    const double v = test::signed_volume(m.V, m.C(c, 0), m.C(c, 1), m.C(c, 2), m.C(c, 3));
    EXPECT_GT(v, 0) << "tet " << c;
    volume += v;
  }
  EXPECT_NEAR(volume, 4.0 / 3.0 * 1000.0, 1e-6) << "octahedron of radius 10";
  EXPECT_GT(m.num_cells(), 8) << "refined to the target edge length";
}

}  // namespace
}  // namespace facehex
