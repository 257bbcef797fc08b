#include "core/io/mesh_io.h"
#include "io_test_util.h"

#include <gtest/gtest.h>

namespace facehex {
namespace {

using test::TempDir;
namespace fs = std::filesystem;

void expect_two_tets(const VolumeMesh& m) {
  ASSERT_EQ(m.num_vertices(), 5);
  ASSERT_EQ(m.num_cells(), 2);
  EXPECT_TRUE(m.is_tet_mesh());
  Eigen::MatrixXi T(2, 4);
  T << 0, 1, 2, 3, 1, 2, 3, 4;
  EXPECT_EQ(m.tets(), T);
  EXPECT_EQ(m.V.row(4), Eigen::RowVector3d(1, 1, 1));
  for (int c = 0; c < 2; ++c) EXPECT_GT(test::signed_volume(m.V, m.C(c, 0), m.C(c, 1), m.C(c, 2), m.C(c, 3)), 0);
}

TEST(TetGen, ZeroBasedWithAttributesMarkersAndComments) {
  for (const char* name : {"tets0.node", "tets0.ele"}) {  // either file of the pair may be given
    const VolumeMesh m = read_volume_mesh(test::data_dir() + "/" + name);
    expect_two_tets(m);
    ASSERT_TRUE(m.point_data.count("tetgen_attributes"));
    EXPECT_EQ(m.point_data.at("tetgen_attributes"), Eigen::MatrixXd::Constant(5, 1, 0.5));
    ASSERT_TRUE(m.point_data.count("tetgen_boundary_marker"));
    EXPECT_EQ(m.point_data.at("tetgen_boundary_marker")(3, 0), 0);
    EXPECT_EQ(m.point_data.at("tetgen_boundary_marker")(4, 0), 1);
    ASSERT_TRUE(m.cell_data.count("tetgen_attributes"));
    EXPECT_EQ(m.cell_data.at("tetgen_attributes"), Eigen::MatrixXd(Eigen::Vector2d(1, 2)));
  }
}

TEST(TetGen, OneBased) {
  const VolumeMesh m = read_volume_mesh(test::data_dir() + "/tets1.ele");
  expect_two_tets(m);
  EXPECT_TRUE(m.point_data.empty());
  EXPECT_TRUE(m.cell_data.empty());
}

// The 1-based pair copied to a scratch folder with one edit applied to the named file.
void expect_edit_fails(const std::string& file, const std::string& from, const std::string& to,
                       const std::string& message) {
  TempDir dir;
  for (const char* ext : {".node", ".ele"}) {
    std::string text = test::read_file(test::data_dir() + "/tets1" + ext);
    if (ext == "." + file) {
      const size_t at = text.find(from);
      ASSERT_NE(at, std::string::npos) << from;
      text.replace(at, from.size(), to);
    }
    test::write_file(dir.file(std::string("m") + ext), text);
  }
  test::expect_error([&] { read_volume_mesh(dir.file("m.node")); }, dir.file("m." + file) + ": " + message);
}

TEST(TetGenErrors, NodeIndexOutOfRange) {
  expect_edit_fails("ele", "2 2 3 4 5", "2 2 3 4 6", "node id 6 out of range 1..5, line 3");
  expect_edit_fails("ele", "1 1 2 3 4", "1 0 2 3 4", "node id 0 out of range 1..5, line 2");
}

TEST(TetGenErrors, CountsDisagree) {
  expect_edit_fails("node", "5 3 0 0", "6 3 0 0", "file ends early: expected point 6 of 6");
  expect_edit_fails("node", "5 3 0 0", "4 3 0 0", "more points than the 4 announced in the header, line 6");
  expect_edit_fails("ele", "2 4 0", "3 4 0", "file ends early: expected tetrahedron 3 of 3");
}

TEST(TetGenErrors, MalformedLines) {
  expect_edit_fails("node", "3 0 1 0", "3 0 one 0", "expected a finite number for a coordinate, found 'one'");
  expect_edit_fails("node", "3 0 1 0", "3 0 1", "expected 4 values");
  expect_edit_fails("node", "3 0 1 0", "7 0 1 0", "point id 7 out of sequence, expected 3, line 4");
  expect_edit_fails("node", "5 3 0 0", "5 2 0 0", "dimension is 2, expected 3");
  expect_edit_fails("ele", "2 4 0", "2 5 0", "nodes per tetrahedron must be 4 or 10");
  expect_edit_fails("ele", "2 2 3 4 5", "2 2 3 3 5", "tetrahedron 2 uses node 3 twice, line 3");
}

TEST(TetGenErrors, MissingSibling) {
  TempDir dir;
  test::write_file(dir.file("lonely.node"), test::read_file(test::data_dir() + "/tets1.node"));
  test::expect_error([&] { read_volume_mesh(dir.file("lonely.node")); }, "found neither lonely.ele");
  test::write_file(dir.file("lonely2.ele"), test::read_file(test::data_dir() + "/tets1.ele"));
  test::expect_error([&] { read_volume_mesh(dir.file("lonely2.ele")); }, "without its node file lonely2.node");
}

}  // namespace
}  // namespace facehex
