#include "core/io/ansys_io.h"
#include "core/io/mesh_io.h"
#include "io_test_util.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <set>

namespace facehex {
namespace {

using test::TempDir;
namespace fs = std::filesystem;

// NWRITE layout: 8-character id, 20-character coordinates; a negative coordinate fills its field and glues to the
// one before ("      11-2.5000000000000E-01...").
std::string fixed_width_line(long id, double x, double y, double z) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "%8ld%20.13E%20.13E%20.13E\n", id, x, y, z);
  return buf;
}

// Two bricks side by side and a prism (collapsed brick, K=L and O=P) on top of the first, with gaps in the node ids
// and every coordinate shifted so that some are negative. Every node line but two is in glued fixed-width form.
struct TinyAnsysMesh {
  std::string node_text, elem_text;
  TinyAnsysMesh() {
    const double s[3] = {-0.25, -0.5, -0.75};
    auto node = [&](long id, double x, double y, double z) {
      node_text += fixed_width_line(id, x + s[0], y + s[1], z + s[2]);
    };
    node(11, 0, 0, 0), node(12, 1, 0, 0), node(13, 1, 1, 0), node(14, 0, 1, 0);
    node(15, 0, 0, 1), node(16, 1, 0, 1), node(17, 1, 1, 1), node(18, 0, 1, 1);
    node(21, 2, 0, 0), node(22, 2, 1, 0), node(23, 2, 0, 1), node(24, 2, 1, 1);
    node(31, 0, 0, 2), node(32, 1, 0, 2);
    node_text += "      33   -0.25   0.5   1.25\n";  // blank-separated lines are fine too
    node_text += "1000 5 5 5\n";                     // unused node
    elem_text =
        "    11    12    13    14    15    16    17    18     1     1     1     0     0     1\n"
        "    12    21    22    13    16    23    24    17     1     1     1     0     0     2\n"
        "    15    16    18    18    31    32    33    33     1     2     1     0     0     7\n";
  }
  void write(const TempDir& dir, const std::string& stem) const {
    test::write_file(dir.file(stem + ".node"), node_text);
    test::write_file(dir.file(stem + ".elem"), elem_text);
  }
};

TEST(AnsysNodeLine, GluedFixedWidthFieldsParse) {
  long id = 0;
  Eigen::Vector3d p;
  ASSERT_TRUE(parse_ansys_node_line("     124-0.5341737707000E-08  77.75542560000     -76.32121660000    ", &id, &p));
  EXPECT_EQ(id, 124);
  EXPECT_EQ(p[0], -0.5341737707000E-08);
  EXPECT_EQ(p[1], 77.75542560000);
  EXPECT_EQ(p[2], -76.32121660000);
  // Both y and z glued as well, trailing blanks stripped.
  ASSERT_TRUE(parse_ansys_node_line("12345678-1.0000000000000E+00-2.0000000000000E+00-3.0000000000000E+00", &id, &p));
  EXPECT_EQ(id, 12345678);
  EXPECT_EQ(p, Eigen::Vector3d(-1, -2, -3));
}

TEST(AnsysNodeLine, BlankSeparated) {
  long id = 0;
  Eigen::Vector3d p;
  ASSERT_TRUE(parse_ansys_node_line("  7 1.5 -2 +3e1", &id, &p));
  EXPECT_EQ(id, 7);
  EXPECT_EQ(p, Eigen::Vector3d(1.5, -2, 30));
}

TEST(AnsysNodeLine, RejectsMalformedLines) {
  long id = 0;
  Eigen::Vector3d p;
  EXPECT_FALSE(parse_ansys_node_line("7 1.5 -2", &id, &p));
  EXPECT_FALSE(parse_ansys_node_line("7 1.5 -2 x", &id, &p));
  EXPECT_FALSE(parse_ansys_node_line("7 1.5 -2 nan", &id, &p));
  EXPECT_FALSE(parse_ansys_node_line("     124-0.5341737707000E-08  77.7554256", &id, &p));  // cut
  EXPECT_FALSE(parse_ansys_node_line("     124-0.5341737707000E-08  77.75542560000     -76.3212166xyz", &id, &p));
}

TEST(Ansys, TinyHexWedgeMesh) {
  TempDir dir;
  TinyAnsysMesh tiny;
  tiny.write(dir, "tiny");
  for (const char* name : {"tiny.elem", "tiny.node"}) {  // .node is ANSYS when a .elem lies beside it
    const VolumeMesh m = read_volume_mesh(dir.file(name));
    ASSERT_EQ(m.num_vertices(), 16);
    ASSERT_EQ(m.num_cells(), 3);
    EXPECT_EQ(m.types, (std::vector<CellType>{CellType::Hex, CellType::Hex, CellType::Wedge}));
    // Node ids 11..18, 21..24, 31..33, 1000 are rows 0..15.
    Eigen::Matrix<int, 3, 8> expected;
    expected << 0, 1, 2, 3, 4, 5, 6, 7,  //
        1, 8, 9, 2, 5, 10, 11, 6,        //
        4, 7, 5, 12, 14, 13, -1, -1;     // ANSYS prism I J K M N O = 15 16 18 31 32 33 -> VTK (I K J M O N)
    EXPECT_EQ(m.C, Eigen::MatrixXi(expected));
    EXPECT_EQ(m.V.row(0), Eigen::RowVector3d(-0.25, -0.5, -0.75));
    EXPECT_EQ(m.V.row(14), Eigen::RowVector3d(-0.25, 0.5, 1.25));
    EXPECT_EQ(m.V.row(15), Eigen::RowVector3d(5, 5, 5));
    ASSERT_TRUE(m.point_data.count("ansys_node_id"));
    EXPECT_EQ(m.point_data.at("ansys_node_id")(8, 0), 21);
    EXPECT_EQ(m.point_data.at("ansys_node_id")(15, 0), 1000);
    ASSERT_TRUE(m.cell_data.count("ansys_element_id"));
    EXPECT_EQ(m.cell_data.at("ansys_element_id"), Eigen::MatrixXd(Eigen::Vector3d(1, 2, 7)));
    // VTK conventions: hex base normal towards the top quad, wedge base normal away from the top triangle.
    for (int c = 0; c < 2; ++c) EXPECT_GT(test::base_normal_towards_top(m, c), 0) << "hex " << c;
    EXPECT_LT(test::base_normal_towards_top(m, 2), 0) << "wedge";
  }
}

// The tiny mesh with one edit applied to its .node or .elem text.
void expect_edit_fails(bool in_elem, const std::string& from, const std::string& to, const std::string& message) {
  TempDir dir;
  TinyAnsysMesh tiny;
  std::string& text = in_elem ? tiny.elem_text : tiny.node_text;
  const size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  tiny.write(dir, "m");
  test::expect_error([&] { read_volume_mesh(dir.file("m.elem")); },
                     dir.file(in_elem ? "m.elem" : "m.node") + ": " + message);
}

TEST(AnsysErrors, UnknownNodeId) {
  expect_edit_fails(true, "    24    17     1", "    25    17     1", "element 2 refers to node 25, which is not in");
}

TEST(AnsysErrors, DuplicateNodeId) { expect_edit_fails(false, "1000 5 5 5", "21 5 5 5", "node id 21 defined twice"); }

TEST(AnsysErrors, OtherDegeneratePatterns) {
  // Only K=L (a pyramid-like collapse) and a fully collapsed top (tet) are not prisms.
  expect_edit_fails(true, "    15    16    18    18    31    32    33    33",
                    "    15    16    18    18    31    32    33    31",
                    "element 7 has nodes 15 16 18 18 31 32 33 31: repeated nodes");
  expect_edit_fails(true, "    15    16    18    18    31    32    33    33",
                    "    15    16    18    18    31    31    31    31", "element 7 has nodes");
  expect_edit_fails(true, "    15    16    18    18    31    32    33    33",
                    "    15    16    16    16    31    32    33    33", "element 7 has nodes");
}

TEST(AnsysErrors, DuplicateElementNumber) {
  expect_edit_fails(true, "0     0     7", "0     0     1", "element number 1 used twice (first on line 1), line 3");
}

TEST(AnsysErrors, ColumnsDisagree) {
  expect_edit_fails(true, "    1     0     0     2\n", "    1     0     2\n",
                    "element line has 13 columns, the first one has 14, line 2");
}

TEST(AnsysErrors, GarbageNodeLine) {
  expect_edit_fails(
      false, "1000 5 5 5", "1000 5 5 five",
      "cannot read node line: expected 'id x y z' (separated by blanks or in columns of 8/20/20/20), line 16");
}

TEST(AnsysErrors, ElemWithoutNodeFile) {
  TempDir dir;
  test::write_file(dir.file("alone.elem"), TinyAnsysMesh().elem_text);
  test::expect_error([&] { read_volume_mesh(dir.file("alone.elem")); }, "without its node file alone.node");
}

// The ArtiSynth reference face (ANSYS files): 6024 bricks and 318 prisms written as collapsed bricks.
TEST(AnsysRealData, ArtisynthReferenceFace) {
  const std::string dir = std::string(FACEHEX_SHARED_DIR) + "/data/standard/artisynth-refface";
  if (!fs::exists(dir + "/newface.elem")) GTEST_SKIP() << "no shared data at " << dir;
  const VolumeMesh m = read_volume_mesh(dir + "/newface.elem");
  EXPECT_EQ(m.num_vertices(), 8720);
  EXPECT_EQ(m.count(CellType::Hex), 6024);
  EXPECT_EQ(m.count(CellType::Wedge), 318);
  EXPECT_EQ(m.num_cells(), 6342);
  // The file is consistently oriented: read right, every cell follows VTK's conventions.
  int wrong_hexes = 0, wrong_wedges = 0;
  for (int c = 0; c < m.num_cells(); ++c) {
    const double d = test::base_normal_towards_top(m, c);
    if (m.types[c] == CellType::Hex && d <= 0) ++wrong_hexes;
    if (m.types[c] == CellType::Wedge && d >= 0) ++wrong_wedges;
  }
  EXPECT_EQ(wrong_hexes, 0);
  EXPECT_EQ(wrong_wedges, 0);
  int wedges_checked = 0;
  for (int c = 0; c < m.num_cells(); ++c) {
    if (m.types[c] != CellType::Wedge) continue;
    std::set<int> distinct;
    for (int k = 0; k < 6; ++k) distinct.insert(m.C(c, k));
    EXPECT_EQ(distinct.size(), 6u) << "wedge " << c;
    EXPECT_EQ(m.C(c, 6), -1);
    ++wedges_checked;
  }
  EXPECT_EQ(wedges_checked, 318);
  // The glued fixed-width lines (node 124 is one) are read, not skipped.
  const Eigen::MatrixXd& ids = m.point_data.at("ansys_node_id");
  int row = -1;
  for (int i = 0; i < ids.rows(); ++i)
    if (ids(i, 0) == 124) row = i;
  ASSERT_GE(row, 0);
  EXPECT_EQ(m.V.row(row), Eigen::RowVector3d(-0.5341737707000E-08, 77.75542560000, -76.32121660000));
  EXPECT_EQ(m.cell_data.at("ansys_element_id")(6341, 0), 6342);
}

}  // namespace
}  // namespace facehex
