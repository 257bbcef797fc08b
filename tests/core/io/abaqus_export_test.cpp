// Abaqus / CalculiX .inp: node order and face numbers in the Abaqus conventions, sets and orientations, the round
// trip through our reader, and the reader's handling of hand-written decks. (ccx itself runs in solver_export_test.)
#include <gtest/gtest.h>

#include <sstream>

#include "core/io/abaqus_io.h"
#include "core/io/fe_sets.h"
#include "core/io/mesh_io.h"
#include "export_test_meshes.h"
#include "io_test_util.h"

namespace facehex {
namespace {

using test::TempDir;

// Elements of a written deck as (type, 1-based node ids), parsed from the text.
std::vector<std::pair<std::string, std::vector<int>>> element_lines(const std::string& text) {
  std::vector<std::pair<std::string, std::vector<int>>> out;
  std::istringstream in(text);
  std::string line, type;
  while (std::getline(in, line)) {
    if (line[0] == '*') {
      type = line.rfind("*ELEMENT, TYPE=", 0) == 0 ? line.substr(15, 4) : "";
      continue;
    }
    if (type.empty()) continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream fields(line);
    int id, node;
    std::vector<int> nodes;
    fields >> id;
    while (fields >> node) nodes.push_back(node);
    out.push_back({type, nodes});
  }
  return out;
}

// det of the isoparametric Jacobian at reference point (r, s, t), with the shape functions of Abaqus' C3D8
// (nodes at (-1,-1,-1), (1,-1,-1), (1,1,-1), (-1,1,-1), then z = +1) and C3D6 (nodes (0,0), (1,0), (0,1) at t = -1,
// then t = +1): both solvers' conventions, written out independently of the exporter.
double isoparametric_det(const std::string& type, const Eigen::MatrixXd& X, double r, double s, double t) {
  Eigen::MatrixXd dN(X.rows(), 3);
  if (type == "C3D8") {
    const double sr[8] = {-1, 1, 1, -1, -1, 1, 1, -1}, ss[8] = {-1, -1, 1, 1, -1, -1, 1, 1},
                 st[8] = {-1, -1, -1, -1, 1, 1, 1, 1};
    for (int a = 0; a < 8; ++a) {
      dN.row(a) << sr[a] * (1 + ss[a] * s) * (1 + st[a] * t) / 8, ss[a] * (1 + sr[a] * r) * (1 + st[a] * t) / 8,
          st[a] * (1 + sr[a] * r) * (1 + ss[a] * s) / 8;
    }
  } else {
    const double tri[3][3] = {{1 - r - s, -1, -1}, {r, 1, 0}, {s, 0, 1}};  // N, dN/dr, dN/ds of the triangle
    for (int a = 0; a < 6; ++a) {
      const int i = a % 3;
      const double h = a < 3 ? (1 - t) / 2 : (1 + t) / 2, dh = a < 3 ? -0.5 : 0.5;
      dN.row(a) << tri[i][1] * h, tri[i][2] * h, tri[i][0] * dh;
    }
  }
  return (X.transpose() * dN).determinant();
}

TEST(AbaqusExport, FaceNumbersFollowTheManual) {
  // From the face node lists (abaqus_io.h) and the node maps: a hex keeps VTK's face order; the wedge's VTK faces
  // (0,1,2), (3,5,4), (0,3,4,1), (1,4,5,2), (2,5,3,0) are Abaqus (1,3,2), (4,5,6), (1,4,6,3), (3,6,5,2), (2,5,4,1).
  for (int f = 0; f < 6; ++f) EXPECT_EQ(io::abaqus_face(CellType::Hex, f), f + 1);
  const int wedge[5] = {1, 2, 5, 4, 3}, tet[4] = {3, 4, 2, 1};
  for (int f = 0; f < 5; ++f) EXPECT_EQ(io::abaqus_face(CellType::Wedge, f), wedge[f]) << f;
  for (int f = 0; f < 4; ++f) EXPECT_EQ(io::abaqus_face(CellType::Tet, f), tet[f]) << f;
}

TEST(AbaqusExport, ElementsArePositiveInTheSolverConvention) {
  TempDir dir;
  const VolumeMesh m = test::hex_wedge_slab();
  const std::string path = dir.file("slab.inp");
  write_volume_mesh(path, m);
  const auto elements = element_lines(test::read_file(path));
  ASSERT_EQ(static_cast<int>(elements.size()), m.num_cells());
  int wedges = 0;
  for (const auto& [type, nodes] : elements) {
    Eigen::MatrixXd X(nodes.size(), 3);
    for (size_t k = 0; k < nodes.size(); ++k) X.row(k) = m.V.row(nodes[k] - 1);
    wedges += type == "C3D6";
    for (double t : {-1.0, 0.0, 1.0}) {
      EXPECT_GT(isoparametric_det(type, X, type == "C3D8" ? t : 1.0 / 3, type == "C3D8" ? -t : 1.0 / 3, t), 0) << type;
    }
  }
  EXPECT_EQ(wedges, m.count(CellType::Wedge));
}

TEST(AbaqusExport, DeckHasSetsSurfacesOrientationsAndShortLines) {
  TempDir dir;
  const VolumeMesh m = test::hex_wedge_slab();
  const std::string path = dir.file("slab.inp");
  write_volume_mesh(path, m);
  const std::string text = test::read_file(path);
  for (const char* needle :
       {"*NODE, NSET=NALL\n", "*ELEMENT, TYPE=C3D8, ELSET=HEX\n", "*ELEMENT, TYPE=C3D6, ELSET=WEDGE\n",
        "*ELSET, ELSET=ALL\nHEX, WEDGE\n", "*NSET, NSET=BONE\n", "*SURFACE, TYPE=ELEMENT, NAME=SKIN_SURF\n",
        "*DISTRIBUTION, NAME=FRAMES, LOCATION=ELEMENT\n, 1., 0., 0., 0., 1., 0.\n1, -1, ",
        "*ORIENTATION, NAME=FRAME, SYSTEM=RECTANGULAR\nFRAMES\n",
        "*SOLID SECTION, ELSET=ALL, MATERIAL=SOFT_TISSUE, ORIENTATION=FRAME\n"}) {
    EXPECT_NE(text.find(needle), std::string::npos) << needle;
  }
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) EXPECT_LE(line.size(), 132u) << "CalculiX reads 132 characters: " << line;
}

TEST(AbaqusExport, CoordinatesFitCalculixFieldsAndReadBackExactlyWhenTheyCan) {
  // CalculiX reads 20 characters per field. 77.755425599999995 is exactly 77.7554256 and -1/3 needs 16 digits, but
  // -1e-9/3 would need 17 digits and an exponent (23 characters): it is rounded to 14.
  TempDir dir;
  VolumeMesh m = test::hex_wedge_slab();
  m.V.row(0) << -1e-9 / 3, 77.755425599999995, -1.0 / 3.0;
  const std::string path = dir.file("slab.inp");
  MeshWriteOptions options;
  options.allow_inverted = true;
  write_volume_mesh(path, m, options);
  const std::string text = test::read_file(path);
  EXPECT_NE(text.find("\n1, -3.3333333333333e-10, 77.7554256, -0.3333333333333333\n"), std::string::npos)
      << text.substr(0, 300);
  const VolumeMesh back = read_volume_mesh(path);
  EXPECT_NEAR(back.V(0, 0), m.V(0, 0), 1e-23);
  EXPECT_EQ(back.V(0, 1), m.V(0, 1));
  EXPECT_EQ(back.V(0, 2), m.V(0, 2));
}

TEST(AbaqusExport, RoundTripKeepsMeshSidesAndFrames) {
  TempDir dir;
  const VolumeMesh m = test::hex_wedge_slab();
  const std::string path = dir.file("slab.inp");
  write_volume_mesh(path, m);
  const VolumeMesh back = read_volume_mesh(path);
  EXPECT_EQ(back.V, m.V);
  EXPECT_EQ(back.C, m.C);
  EXPECT_EQ(back.types, m.types);
  EXPECT_EQ(back.point_data.at(kSideMaskArray), m.point_data.at(kSideMaskArray));
  const MaterialFrames frames = *export_frames(m);
  EXPECT_LT((back.cell_data.at("frame_e1") - frames.e1).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((back.cell_data.at("frame_e2") - frames.e2).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((back.cell_data.at("frame_e3") - frames.e3).cwiseAbs().maxCoeff(), 1e-9);
  // ... and writing what was read gives the same deck (frames now from the stored arrays).
  const std::string again = dir.file("again.inp");
  write_volume_mesh(again, back);
  EXPECT_EQ(test::read_file(again), test::read_file(path));
}

TEST(AbaqusReader, ReadsHandWrittenDecks) {
  TempDir dir;
  const std::string path = dir.file("hand.inp");
  test::write_file(path,
                   "*Heading\n** a comment\n*Node\n 10, 0., 0., 0.\n 11, 1., 0., 0.\n 12, 1., 1., 0.\n 13, 0., 1., 0.\n"
                   " 14, 0., 0., 1.\n 15, 1., 0., 1.\n 16, 1., 1., 1.\n 17, 0., 1., 1.\n 18, 0., 0., 2.\n"
                   "*Element, type=C3D8R, elset=brick\n7, 10, 11, 12, 13,\n 14, 15, 16, 17\n"
                   "*element, type=c3d4\n3, 14, 15, 17, 18\n*Nset, nset=skin, generate\n 14, 18, 1\n"
                   "*Nset, nset=Bone\n10, 11\n12, 13\n*Material, name=X\n*Elastic\n1., 0.3\n");
  const VolumeMesh m = read_volume_mesh(path);
  ASSERT_EQ(m.num_cells(), 2);
  EXPECT_EQ(m.types, (std::vector<CellType>{CellType::Tet, CellType::Hex})) << "ordered by element id";
  EXPECT_EQ(m.C.row(1).head(8), (Eigen::RowVectorXi(8) << 0, 1, 2, 3, 4, 5, 6, 7).finished());
  const Eigen::MatrixXd& mask = m.point_data.at(kSideMaskArray);
  EXPECT_EQ(mask(0), side_bit(W0));
  EXPECT_EQ(mask(8), side_bit(W1));
  EXPECT_EQ(m.cell_data.count("frame_e1"), 0u);
}

TEST(AbaqusReader, ErrorsNameFileAndLine) {
  TempDir dir;
  const std::string nodes = "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {nodes + "*ELEMENT, TYPE=C3D10\n1, 1, 2, 3, 4\n", "unsupported element type C3D10"},
      {nodes + "*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 9\n", "refers to unknown node 9"},
      {nodes + "*ELEMENT, TYPE=C3D4\n1, 1, 2, 3\n", "element 1 is incomplete"},
      {nodes + "*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 4, 4\n", "needs 4 nodes"},
      {nodes + "*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, x\n", "line 7"},
      {nodes + "*INCLUDE, INPUT=more.inp\n", "*INCLUDE is not supported"},
      {nodes, "no solid elements"},
      {"1, 2, 3\n", "expected a keyword line"},
  };
  for (const auto& [content, message] : cases) {
    const std::string path = dir.file("bad.inp");
    test::write_file(path, content);
    test::expect_error([&] { read_volume_mesh(path); }, "bad.inp", message);
    test::expect_error([&] { read_volume_mesh(path); }, message, content);
  }
}

}  // namespace
}  // namespace facehex
