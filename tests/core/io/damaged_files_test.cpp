// Files damaged in one declared size: each is an Error naming the file and the problem, never a crash, a hang, a
// runaway allocation or a plausible mesh. The cases are the reproducers found by fuzzing the readers.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>

#include "core/io/mesh_bytes.h"
#include "core/io/mesh_io.h"
#include "core/util/child_process.h"
#include "export_test_meshes.h"
#include "io_test_util.h"

namespace facehex {
namespace {

using test::TempDir;

// A one-tet VTK XML file in ASCII, with the given declared sizes and connectivity.
std::string vtu(const std::string& points, const std::string& cells, const std::string& components,
                const std::string& last_node, const std::string& offset) {
  return R"(<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">
  <UnstructuredGrid>
    <Piece NumberOfPoints=")" +
         points + R"(" NumberOfCells=")" + cells + R"(">
      <PointData>
        <DataArray type="Float64" Name="f" NumberOfComponents=")" +
         components + R"(" format="ascii">0 1 2 3</DataArray>
      </PointData>
      <Points>
        <DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0 0 1 0 0 0 1 0 0 0 1</DataArray>
      </Points>
      <Cells>
        <DataArray type="Int64" Name="connectivity" format="ascii">0 1 2 )" +
         last_node + R"(</DataArray>
        <DataArray type="Int64" Name="offsets" format="ascii">)" +
         offset + R"(</DataArray>
        <DataArray type="UInt8" Name="types" format="ascii">10</DataArray>
      </Cells>
    </Piece>
  </UnstructuredGrid>
</VTKFile>
)";
}

// A one-tet legacy VTK file in ASCII with the given CELLS line and POINTS count.
std::string legacy_vtk(const std::string& points, const std::string& cells) {
  return "# vtk DataFile Version 3.0\ntest\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS " + points +
         " double\n0 0 0 1 0 0 0 1 0 0 0 1\nCELLS " + cells + "\n4 0 1 2 3\nCELL_TYPES 1\n10\n";
}

void expect_quick_error(const std::string& file, const std::string& needle) {
  const auto start = std::chrono::steady_clock::now();
  test::expect_error([&] { read_volume_mesh(file); }, needle, file);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10) << file;
}

TEST(DamagedFiles, TheUndamagedSamplesRead) {
  TempDir dir;
  test::write_file(dir.file("good.vtu"), vtu("4", "1", "1", "3", "4"));
  test::write_file(dir.file("good.vtk"), legacy_vtk("4", "1 5"));
  for (const char* name : {"good.vtu", "good.vtk"}) {
    const VolumeMesh m = read_volume_mesh(dir.file(name));
    EXPECT_EQ(m.num_vertices(), 4) << name;
    EXPECT_EQ(m.num_cells(), 1) << name;
  }
}

TEST(DamagedFiles, NegativeOrHugeCountsInVtkXml) {
  TempDir dir;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {vtu("-1", "1", "1", "3", "4"), "NumberOfPoints=\"-1\" is not a count"},
      {vtu("4", "-1", "1", "3", "4"), "NumberOfCells=\"-1\" is not a count"},
      {vtu("4", "1", "2147483648", "3", "4"), "NumberOfComponents=\"2147483648\" is not a count"},
      {vtu("4", "1", "0", "3", "4"), "NumberOfComponents=\"0\" is not a count"},
      {vtu("4", "1", "1", "3", "400"), "connectivity"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    const std::string file = dir.file("bad" + std::to_string(i) + ".vtu");
    test::write_file(file, cases[i].first);
    expect_quick_error(file, cases[i].second);
  }
}

TEST(DamagedFiles, AnIndexPast32BitsIsNotWrappedIntoAValidOne) {
  TempDir dir;
  const std::string file = dir.file("wrap.vtu");
  test::write_file(file, vtu("4", "1", "1", std::to_string((1LL << 32) + 3), "4"));
  expect_quick_error(file, "refers to point 4294967299 of 4");
}

TEST(DamagedFiles, LegacyVtkWithMoreCellsOrPointsThanItHolds) {
  TempDir dir;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {legacy_vtk("4", "100 500"), "CELLS declares 500 numbers, the file holds 5"},
      {legacy_vtk("4", "1 2000000000"), "CELLS declares 2000000000 numbers"},
      {legacy_vtk("4000000000", "1 5"), "reading legacy VTK"},
      // Fewer numbers declared than the row holds: VTK's reader would run past its buffer (a fuzzer's find).
      {legacy_vtk("4", "1 2"), "cell 1 of 1 runs past the CELLS section's declared 2 numbers"},
      {legacy_vtk("4", "1 7"), "CELLS declares 7 numbers, the file holds 5"},
      {legacy_vtk("4", "2 5"), "cell 2 of 2 runs past"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    const std::string file = dir.file("bad" + std::to_string(i) + ".vtk");
    test::write_file(file, cases[i].first);
    expect_quick_error(file, cases[i].second);
  }
}

// The same check on a binary file's CELLS section (format 4: big-endian int32 rows, as older writers make it).
TEST(DamagedFiles, ABinaryLegacyVtkWhoseCellsRunPastTheirSectionIsRefused) {
  const auto big_endian = [](auto value) {
    std::string b(sizeof value, '\0');
    std::memcpy(b.data(), &value, sizeof value);
    std::reverse(b.begin(), b.end());
    return b;
  };
  const auto file = [&](std::int32_t count) {
    std::string f = "# vtk DataFile Version 3.0\ntest\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n";
    for (const double x : {0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1.}) f += big_endian(x);
    f += "\nCELLS 1 5\n";
    for (const std::int32_t v : {count, 0, 1, 2, 3}) f += big_endian(v);
    return f + "\nCELL_TYPES 1\n" + big_endian(std::int32_t{10}) + "\n";
  };
  TempDir dir;
  test::write_file(dir.file("good.vtk"), file(4));
  EXPECT_EQ(read_volume_mesh(dir.file("good.vtk")).num_cells(), 1);
  test::write_file(dir.file("bad.vtk"), file(5000));
  expect_quick_error(dir.file("bad.vtk"), "cell 1 of 1 runs past the CELLS section's declared 5 numbers");
}

TEST(DamagedFiles, EveryByteOfABinaryVtkCutOrFlippedIsAnErrorOrTheSameMesh) {
  // The sample mesh in binary legacy VTK: flipping any one byte of the header and the cell section (offsets and
  // connectivity) gives an Error naming the file or a mesh that passes the mesh checks, never a crash.
  TempDir dir;
  write_volume_mesh(dir.file("good.vtk"), test::sample_mesh());
  const std::string good = test::read_file(dir.file("good.vtk"));
  const size_t cells = good.find("CELLS");
  ASSERT_NE(cells, std::string::npos);
  int errors = 0;
  for (size_t at = cells; at < std::min(good.size(), cells + 160); at += 3) {
    std::string bad = good;
    bad[at] = static_cast<char>(bad[at] ^ 0x5a);
    const std::string file = dir.file("flip.vtk");
    test::write_file(file, bad);
    try {
      read_volume_mesh(file);
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
      ++errors;
    }
  }
  EXPECT_GT(errors, 0);
}

TEST(DamagedFiles, ASurfaceWithANegativeCountIsAnErrorAndAGoodOneStillReads) {
  TempDir dir;
  SurfaceMesh s;
  s.V.resize(4, 3);
  s.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  s.F.resize(4, 3);
  s.F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  write_surface_mesh(dir.file("good.vtp"), s);
  const SurfaceMesh back = read_surface_mesh(dir.file("good.vtp"));
  EXPECT_EQ(back.V.rows(), 4);  // the reader may renumber the points (it merges duplicates)
  EXPECT_EQ(back.F.rows(), 4);
  std::string text = test::read_file(dir.file("good.vtp"));
  const size_t at = text.find("NumberOfPolys=\"");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, text.find('"', at + 15) - at + 1, "NumberOfPolys=\"-1\"");
  test::write_file(dir.file("bad.vtp"), text);
  test::expect_error([&] { read_surface_mesh(dir.file("bad.vtp")); }, "NumberOfPolys=\"-1\" is not a count",
                     dir.file("bad.vtp"));
}

// An .inp FaceHex wrote, cut at a line end anywhere before its last line, is refused: not read as a smaller mesh.
TEST(DamagedFiles, AnAbaqusDeckCutAtALineEndIsRefused) {
  TempDir dir;
  const std::string whole = dir.file("whole.inp");
  write_volume_mesh(whole, test::hex_wedge_slab());
  EXPECT_EQ(read_volume_mesh(whole).num_cells(), test::hex_wedge_slab().num_cells());
  const std::string text = test::read_file(whole);
  std::vector<size_t> line_ends;
  for (size_t at = text.find('\n'); at + 1 < text.size(); at = text.find('\n', at + 1)) line_ends.push_back(at + 1);
  // Cuts among the nodes, the elements, the side sets and just before the last line.
  for (const double fraction : {0.1, 0.3, 0.6, 0.9, 1.0}) {
    const size_t cut = line_ends[std::min(line_ends.size() - 1, static_cast<size_t>(fraction * line_ends.size()))];
    const std::string file = dir.file("cut" + std::to_string(cut) + ".inp");
    test::write_prefix(whole, file, cut);
    test::expect_error([&] { read_volume_mesh(file); }, file + ": ", "cut at byte " + std::to_string(cut));
    test::expect_error([&] { read_volume_mesh(file); }, "cut short", "cut at byte " + std::to_string(cut));
  }
}

// An XML character reference the FEBio reader cannot decode, or elements nested without end, are errors naming the
// file (they were an exception naming nothing and a stack overflow); sound references decode.
TEST(DamagedFiles, FebioCharacterReferencesAndNestingAreChecked) {
  TempDir dir;
  const std::string sound = test::read_file(std::string(FACEHEX_TEST_DATA_DIR) + "/export/hex_wedge.feb");
  const auto with_first_node = [&](const std::string& text) {
    std::string s = sound;
    const std::string node = "<node id=\"1\">0,0,0</node>";
    return s.replace(s.find(node), node.size(), "<node id=\"1\">" + text + "</node>");
  };
  test::write_file(dir.file("decoded.feb"), with_first_node("&#50;,&#x33;,0"));
  EXPECT_EQ(read_volume_mesh(dir.file("decoded.feb")).V.row(0), Eigen::RowVector3d(2, 3, 0));
  int n = 0;
  for (const char* reference : {"&#x;", "&#xZZ;", "&#99999999999;", "&#0;", "&#-5;"}) {
    const std::string file = dir.file("bad" + std::to_string(n++) + ".feb");
    test::write_file(file, with_first_node(std::string(reference) + ",0,0"));
    test::expect_error([&] { read_volume_mesh(file); }, file + ": '" + reference + "' is not a character");
  }
  std::string deep;
  for (int i = 0; i < 100000; ++i) deep += "<a>";
  test::write_file(dir.file("deep.feb"), deep);
  test::expect_error([&] { read_volume_mesh(dir.file("deep.feb")); },
                     dir.file("deep.feb") + ": elements nested more than 100 deep");
}

// A node set generated over a damaged range is refused before it fills memory.
TEST(DamagedFiles, AnAbaqusNodeSetRangeBeyondTheNodesIsRefused) {
  TempDir dir;
  const std::string deck =
      "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 4\n"
      "*NSET, NSET=S, GENERATE\n";
  test::write_file(dir.file("sound.inp"), deck + "1, 4, 1\n");
  EXPECT_EQ(read_volume_mesh(dir.file("sound.inp")).num_cells(), 1);
  test::write_file(dir.file("huge.inp"), deck + "1, 100000000000, 1\n");
  expect_quick_error(dir.file("huge.inp"), "huge.inp: *NSET, GENERATE covers more ids than the 4 nodes defined");
}

// Two elements on the same nodes double the stiffness there, and no solver says so: the FE exports refuse them, even
// when forced, and leave no file.
TEST(DamagedFiles, DuplicateCellsAreNotExported) {
  TempDir dir;
  VolumeMesh m = test::hex_wedge_slab();
  const int n = m.num_cells();
  m.C.conservativeResize(n + 1, Eigen::NoChange);
  m.C.row(n) = m.C.row(2);
  std::swap(m.C(n, 0), m.C(n, 1));  // the same nodes in another order
  m.types.push_back(m.types[2]);
  for (auto& [name, a] : m.cell_data) a.conservativeResize(n + 1, Eigen::NoChange), a.row(n) = a.row(2);
  for (const char* name : {"dup.inp", "dup.feb"})
    for (const bool forced : {false, true}) {
      MeshWriteOptions options;
      options.allow_inverted = forced;
      const std::string file = dir.file(name);
      test::expect_error([&] { write_volume_mesh(file, m, options); },
                         file + ": refusing to export: 1 of " + std::to_string(n + 1) +
                             " elements repeat the nodes of an earlier element (element ids " + std::to_string(n + 1));
    }
  EXPECT_TRUE(dir.entries().empty());
}

// A reader that runs out of memory says which file it was reading: here a child process with a small memory budget
// reads a TetGen file larger than that budget.
TEST(DamagedFiles, RunningOutOfMemoryNamesTheFile) {
  TempDir dir;
  std::string nodes = "2000000 3 0 0\n";
  for (int i = 0; i < 2000000; ++i) nodes += std::to_string(i) + " 0.5 0.25 0.125\n";
  test::write_file(dir.file("big.node"), nodes);
  test::write_file(dir.file("big.ele"), "1 4 0\n0 0 1 2 3\n");
  ChildLimits limits;
  limits.memory_bytes = std::size_t{8} << 20;
  limits.seconds = 60;
  test::expect_error(
      [&] {
        compute_in_child(
            "the test", "reading", [&] { return io::to_bytes(read_volume_mesh(dir.file("big.node"))); }, limits);
      },
      dir.file("big.node") + ": not enough memory to read it");
}

TEST(MeshBytes, ASurfaceRoundTripIsBitIdentical) {
  SurfaceMesh s;
  s.V = Eigen::MatrixXd::Random(5, 3);
  s.F.resize(2, 3);
  s.F << 0, 1, 2, 2, 3, 4;
  s.labels = Eigen::VectorXi::LinSpaced(2, 1, 2);
  const SurfaceMesh back = io::surface_from_bytes(io::to_bytes(s), "s");
  EXPECT_EQ(back.V, s.V);
  EXPECT_EQ(back.F, s.F);
  EXPECT_EQ(back.labels, s.labels);
}

TEST(MeshBytes, ARoundTripIsBitIdenticalAndDamagedBytesAreRefused) {
  const VolumeMesh m = test::sample_mesh();
  const std::vector<char> bytes = io::to_bytes(m);
  const VolumeMesh back = io::mesh_from_bytes(bytes, "s");
  EXPECT_EQ(back.V, m.V);
  EXPECT_EQ(back.C, m.C);
  EXPECT_EQ(back.types, m.types);
  EXPECT_EQ(back.point_data, m.point_data);
  EXPECT_EQ(back.cell_data, m.cell_data);
  for (size_t cut : {size_t{0}, size_t{5}, bytes.size() / 2, bytes.size() - 1})
    test::expect_error([&] { io::mesh_from_bytes(std::vector<char>(bytes.begin(), bytes.begin() + cut), "s"); }, "s: ");
}

}  // namespace
}  // namespace facehex
