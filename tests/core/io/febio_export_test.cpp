// FEBio .feb: the written file has the structure of a hand-written FEBio 4.0 reference model
// (tests/data/export/hex_wedge.feb) element for element, and reads back with our reader.
#include <gtest/gtest.h>

#include <map>
#include <sstream>

#include "core/io/fe_sets.h"
#include "core/io/febio_io.h"
#include "core/io/mesh_io.h"
#include "export_test_meshes.h"
#include "io_test_util.h"

namespace facehex {
namespace {

using test::TempDir;

// The model of the reference file: a unit hex with a roof wedge on top, sides u0, u1, w0, w1, uvw = (x, y, z/1.5).
VolumeMesh hex_with_roof() {
  VolumeMesh m;
  m.V.resize(10, 3);
  m.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1, 0, 0.5, 1.5, 1, 0.5, 1.5;
  m.C = Eigen::MatrixXi::Constant(2, 8, -1);
  m.C.row(0) << 0, 1, 2, 3, 4, 5, 6, 7;
  m.C.row(1).head(6) << 4, 8, 7, 5, 9, 6;  // triangle (4, 8, 7) at x = 0, normal -x: away from (5, 9, 6)
  m.types = {CellType::Hex, CellType::Wedge};
  Eigen::VectorXd mask = Eigen::VectorXd::Zero(10);
  for (int v : {0, 3, 4, 7, 8}) mask(v) += side_bit(U0);
  for (int v : {1, 2, 5, 6, 9}) mask(v) += side_bit(U1);
  for (int v : {0, 1, 2, 3}) mask(v) += side_bit(W0);
  for (int v : {4, 5, 6, 7, 8, 9}) mask(v) += side_bit(W1);
  m.point_data[kSideMaskArray] = mask;
  Eigen::MatrixXd uvw = m.V;
  uvw.col(2) /= 1.5;
  m.point_data["uvw"] = uvw;
  return m;
}

// Every XML element as "path" + attributes + trimmed text, scanned independently of the product's reader.
struct XmlRecord {
  std::string path;
  std::map<std::string, std::string> attributes;
  std::string text;
};

std::vector<XmlRecord> scan_xml(const std::string& xml) {
  struct Open {
    size_t record, text_start;
    bool has_children;
  };
  std::vector<XmlRecord> records;
  std::vector<Open> open;
  for (size_t pos = xml.find('<'); pos != std::string::npos; pos = xml.find('<', pos)) {
    if (xml.compare(pos, 4, "<!--") == 0) {
      pos = xml.find("-->", pos);
      continue;
    }
    const size_t end = xml.find('>', pos);
    const std::string tag = xml.substr(pos + 1, end - pos - 1);
    if (tag[0] == '/') {
      if (!open.back().has_children) {
        std::string text = xml.substr(open.back().text_start, pos - open.back().text_start);
        text.erase(0, text.find_first_not_of(" \n"));
        text.erase(text.find_last_not_of(" \n") + 1);
        records[open.back().record].text = text;
      }
      open.pop_back();
    } else if (tag[0] != '?') {
      XmlRecord r;
      std::istringstream(tag) >> r.path;
      if (!open.empty()) {
        r.path = records[open.back().record].path + "/" + r.path;
        open.back().has_children = true;
      }
      for (size_t q = tag.find('='); q != std::string::npos; q = tag.find('=', q + 1)) {
        const size_t name_start = tag.rfind(' ', q) + 1;
        r.attributes[tag.substr(name_start, q - name_start)] = tag.substr(q + 2, tag.find('"', q + 2) - q - 2);
      }
      records.push_back(r);
      if (tag.back() != '/') open.push_back({records.size() - 1, end + 1, false});
    }
    pos = end + 1;
  }
  return records;
}

std::map<std::string, int> outline(const std::vector<XmlRecord>& records) {
  std::map<std::string, int> counts;
  for (const XmlRecord& r : records) {
    std::string key = r.path + "[";
    for (const auto& [name, value] : r.attributes) key += name + " ";
    ++counts[key + "]"];
  }
  return counts;
}

std::vector<double> numbers(std::string text) {
  std::replace(text.begin(), text.end(), ',', ' ');
  std::istringstream in(text);
  std::vector<double> out;
  for (double x; in >> x;) out.push_back(x);
  return out;
}

const std::string kReference = std::string(FACEHEX_TEST_DATA_DIR) + "/export/hex_wedge.feb";

TEST(FebioExport, StructureMatchesTheHandWrittenReference) {
  TempDir dir;
  const std::string path = dir.file("model.feb");
  write_volume_mesh(path, hex_with_roof());
  const std::vector<XmlRecord> ours = scan_xml(test::read_file(path));
  const std::vector<XmlRecord> reference = scan_xml(test::read_file(kReference));
  ASSERT_GT(reference.size(), 50u);
  EXPECT_EQ(outline(ours), outline(reference));
  ASSERT_EQ(ours.size(), reference.size());
  for (size_t i = 0; i < ours.size(); ++i) {
    const XmlRecord &a = ours[i], &b = reference[i];
    EXPECT_EQ(a.path, b.path);
    if (a.path == "febio_spec/Mesh/Nodes") continue;  // the object name is free
    EXPECT_EQ(a.attributes, b.attributes) << a.path;
    const bool numeric = a.path.find("/node") != std::string::npos || a.path.find("/a") != std::string::npos ||
                         a.path.find("/d") != std::string::npos || a.path.find("/density") != std::string::npos;
    if (numeric) {
      const std::vector<double> x = numbers(a.text), y = numbers(b.text);
      ASSERT_EQ(x.size(), y.size()) << a.path;
      for (size_t k = 0; k < x.size(); ++k) EXPECT_NEAR(x[k], y[k], 1e-12) << a.path;
    } else {
      EXPECT_EQ(a.text, b.text) << a.path << " " << a.attributes.size();
    }
  }
}

TEST(FebioExport, RoundTripKeepsMeshSidesAndFrames) {
  TempDir dir;
  for (const VolumeMesh& m : {hex_with_roof(), test::hex_wedge_slab()}) {
    const std::string path = dir.file("model.feb");
    write_volume_mesh(path, m);
    const VolumeMesh back = read_volume_mesh(path);
    EXPECT_EQ(back.V, m.V);
    EXPECT_EQ(back.C, m.C);
    EXPECT_EQ(back.types, m.types);
    EXPECT_EQ(back.point_data.at(kSideMaskArray), m.point_data.at(kSideMaskArray));
    const MaterialFrames frames = *export_frames(m);
    EXPECT_LT((back.cell_data.at("frame_e1") - frames.e1).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((back.cell_data.at("frame_e3") - frames.e3).cwiseAbs().maxCoeff(), 1e-12);
  }
}

TEST(FebioReader, ReadsTheReferenceFile) {
  const VolumeMesh m = read_volume_mesh(kReference);
  const VolumeMesh expected = hex_with_roof();
  EXPECT_EQ(m.V, expected.V);
  EXPECT_EQ(m.C, expected.C);
  EXPECT_EQ(m.point_data.at(kSideMaskArray), expected.point_data.at(kSideMaskArray));
  EXPECT_EQ(m.cell_data.at("frame_e2").row(1), Eigen::RowVector3d(0, 1, 0));
}

TEST(FebioReader, ErrorsNameFileAndLine) {
  TempDir dir;
  const std::string head =
      "<?xml version=\"1.0\"?>\n<febio_spec version=\"4.0\">\n<Mesh>\n<Nodes>\n"
      "<node id=\"1\">0,0,0</node><node id=\"2\">1,0,0</node>\n"
      "<node id=\"3\">0,1,0</node><node id=\"4\">0,0,1</node>\n</Nodes>\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"<febio_spec version=\"3.0\"/>", "version 3.0 is not supported"},
      {head + "<Elements type=\"hex20\" name=\"P\"/>\n</Mesh>\n</febio_spec>\n", "unsupported element type hex20"},
      {head + "<Elements type=\"tet4\" name=\"P\"><elem id=\"1\">1,2,3</elem></Elements></Mesh></febio_spec>",
       "tet4 element needs 4 nodes, found 3, line 8"},
      {head + "<Elements type=\"tet4\" name=\"P\"><elem id=\"1\">1,2,3,7</elem></Elements></Mesh></febio_spec>",
       "refers to unknown node 7"},
      {head + "</febio_spec>\n", "mismatched end tag, expected </Mesh>"},
      {head, "element <Mesh> is not closed"},
      {"<?xml version=\"1.0\"?>\n<something/>", "not an FEBio file"},
  };
  for (const auto& [content, message] : cases) {
    const std::string path = dir.file("bad.feb");
    test::write_file(path, content);
    test::expect_error([&] { read_volume_mesh(path); }, "bad.feb: ", message);
    test::expect_error([&] { read_volume_mesh(path); }, message, content);
  }
}

}  // namespace
}  // namespace facehex
