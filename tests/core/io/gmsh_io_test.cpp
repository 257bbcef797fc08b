#include "core/io/mesh_io.h"
#include "io_test_util.h"

#include <gtest/gtest.h>

namespace facehex {
namespace {

using test::TempDir;
namespace fs = std::filesystem;

// Both files hold the same mesh (tests/data/io): a unit hex, a prism on top of it and a tet beside it, plus a point,
// a line and a triangle that must be skipped, with node ids 10, 20, ..., 120.
class GmshHandWritten : public ::testing::TestWithParam<std::string> {};

TEST_P(GmshHandWritten, ReadsVolumeElementsAndReordersPrisms) {
  const VolumeMesh m = read_volume_mesh(test::data_dir() + "/" + GetParam());
  ASSERT_EQ(m.num_vertices(), 12);
  ASSERT_EQ(m.num_cells(), 3);
  EXPECT_EQ(m.count(CellType::Hex), 1);
  EXPECT_EQ(m.count(CellType::Wedge), 1);
  EXPECT_EQ(m.count(CellType::Tet), 1);
  EXPECT_EQ(m.V.row(11), Eigen::RowVector3d(2, 0, 0)) << "node 120 is the 12th";
  Eigen::Matrix<int, 3, 8> expected;
  expected << 0, 1, 2, 3, 4, 5, 6, 7,  //
      4, 7, 5, 8, 10, 9, -1, -1,       // Gmsh prism (50 60 80 90 100 110) -> VTK wedge (50 80 60 90 110 100)
      1, 11, 2, 5, -1, -1, -1, -1;
  EXPECT_EQ(m.C, Eigen::MatrixXi(expected));
  EXPECT_EQ(m.types, (std::vector<CellType>{CellType::Hex, CellType::Wedge, CellType::Tet}));
  // VTK wedge convention: the normal of (0, 1, 2) points away from the top triangle.
  EXPECT_GT(test::base_normal_towards_top(m, 0), 0);
  EXPECT_LT(test::base_normal_towards_top(m, 1), 0);
  EXPECT_GT(test::signed_volume(m.V, m.C(2, 0), m.C(2, 1), m.C(2, 2), m.C(2, 3)), 0);
  ASSERT_TRUE(m.cell_data.count("gmsh_physical"));
  EXPECT_EQ(m.cell_data.at("gmsh_physical"), Eigen::MatrixXd(Eigen::Vector3d(10, 20, 10)));
}

TEST_P(GmshHandWritten, IsReadTheSameAfterWritingAs41) {
  TempDir dir;
  const VolumeMesh m = read_volume_mesh(test::data_dir() + "/" + GetParam());
  write_volume_mesh(dir.file("again.msh"), m);
  const VolumeMesh back = read_volume_mesh(dir.file("again.msh"));
  EXPECT_EQ(back.V, m.V);
  EXPECT_EQ(back.C, m.C);
  EXPECT_EQ(back.cell_data.at("gmsh_physical"), m.cell_data.at("gmsh_physical"));
}

INSTANTIATE_TEST_SUITE_P(Versions, GmshHandWritten,
                         ::testing::Values("hex_prism_tet_v22.msh", "hex_prism_tet_v41.msh"));

// The v2.2 sample with one edit applied, expected to fail with `message`.
void expect_v22_edit_fails(const std::string& from, const std::string& to, const std::string& message) {
  TempDir dir;
  std::string text = test::read_file(test::data_dir() + "/hex_prism_tet_v22.msh");
  const size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  const std::string path = dir.file("edited.msh");
  test::write_file(path, text);
  test::expect_error([&] { read_volume_mesh(path); }, message, "after replacing '" + from + "'");
  test::expect_error([&] { read_volume_mesh(path); }, path);
}

TEST(GmshErrors, BinaryFilesAreRejectedClearly) {
  expect_v22_edit_fails("2.2 0 8", "2.2 1 8", "binary .msh not supported");
}

TEST(GmshErrors, UnsupportedVersion) { expect_v22_edit_fails("2.2 0 8", "4 0 8", "version 4 is not supported"); }

TEST(GmshErrors, PyramidsAreNamed) {
  expect_v22_edit_fails("7 4 2 10 3 20 120 30 60", "7 7 2 10 3 20 120 30 60 70", "unsupported volume element type 7");
}

TEST(GmshErrors, UnknownNode) {
  expect_v22_edit_fails("7 4 2 10 3 20 120 30 60", "7 4 2 10 3 20 121 30 60", "unknown node 121, line 32");
}

TEST(GmshErrors, WrongNodeCountOfAnElement) {
  expect_v22_edit_fails("7 4 2 10 3 20 120 30 60", "7 4 2 10 3 20 120 30", "needs 4 nodes, found 3");
}

TEST(GmshErrors, NodeCountDisagrees) {
  expect_v22_edit_fails("$Nodes\n12", "$Nodes\n13", "section ended after 12 nodes, but 13 were announced");
  expect_v22_edit_fails("$Nodes\n12", "$Nodes\n11", "more records than the section header announced");
}

TEST(GmshErrors, ElementCountDisagrees) {
  expect_v22_edit_fails("$Elements\n7", "$Elements\n8", "but 8 were announced");
}

TEST(GmshErrors, DuplicateNode) { expect_v22_edit_fails("20 1 0 0", "10 1 0 0", "node 10 defined twice"); }

TEST(GmshErrors, NonNumericCoordinate) { expect_v22_edit_fails("70 1 1 1", "70 1 x 1", "found 'x', line 17"); }

TEST(GmshErrors, NotAGmshFile) { expect_v22_edit_fails("$MeshFormat", "$Mesh", "not a Gmsh file"); }

TEST(GmshErrors, OnlySurfaceElements) {
  TempDir dir;
  const std::string path = dir.file("surface.msh");
  test::write_file(path,
                   "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n"
                   "$Elements\n1\n1 2 0 1 2 3\n$EndElements\n");
  test::expect_error([&] { read_volume_mesh(path); }, "no volume elements");
}

}  // namespace
}  // namespace facehex
