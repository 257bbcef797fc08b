#include "core/io/febio_io.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <sstream>
#include <unordered_map>

#include "core/io/fe_sets.h"
#include "core/io/io_util.h"
#include "core/mesh/cell_faces.h"
#include "core/util/error.h"

namespace facehex::io {

namespace {

constexpr const char* kMaterial = "soft_tissue";

const char* febio_type(CellType type) {
  switch (type) {
    case CellType::Hex:
      return "hex8";
    case CellType::Wedge:
      return "penta6";
    case CellType::Tet:
      return "tet4";
  }
  return "";
}

// ---- A small XML reader: elements, attributes and character data, enough for FEBio files (no namespaces, no DTD).

struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;  // character data directly inside, entities decoded
  std::vector<XmlElement> children;
  int line = 0;
};

class XmlParser {
 public:
  explicit XmlParser(const std::string& path) : path_(path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    text_ = ss.str();
  }

  XmlElement parse() {
    skip_misc();
    if (!starts_with("<")) fail("not an XML file: no root element");
    XmlElement root = element();
    skip_misc();
    if (pos_ < text_.size()) fail("content after the root element </" + root.name + ">");
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& problem) {
    throw Error(path_, problem + ", line " + std::to_string(line()));
  }
  // The line of pos_, counted incrementally: pos_ only moves forward.
  int line() {
    line_ += static_cast<int>(std::count(text_.begin() + counted_, text_.begin() + pos_, '\n'));
    counted_ = pos_;
    return line_;
  }
  bool starts_with(const char* s) const { return text_.compare(pos_, std::char_traits<char>::length(s), s) == 0; }
  void skip_space() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }
  void skip_past(const char* end) {
    const size_t at = text_.find(end, pos_);
    if (at == std::string::npos) fail(std::string("unterminated markup, expected '") + end + "'");
    pos_ = at + std::char_traits<char>::length(end);
  }
  // Declarations, processing instructions, comments and white space between elements.
  void skip_misc() {
    while (true) {
      skip_space();
      if (starts_with("<?")) {
        skip_past("?>");
      } else if (starts_with("<!--")) {
        skip_past("-->");
      } else if (starts_with("<!")) {
        skip_past(">");
      } else {
        return;
      }
    }
  }
  std::string name() {
    const size_t start = pos_;
    while (pos_ < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[pos_])) ||
                                   std::string_view("_-.:").find(text_[pos_]) != std::string_view::npos)) {
      ++pos_;
    }
    if (pos_ == start) fail("expected a name");
    return text_.substr(start, pos_ - start);
  }
  std::string decode(std::string_view s) {
    std::string out;
    for (size_t i = 0; i < s.size(); ++i) {
      if (s[i] != '&') {
        out += s[i];
        continue;
      }
      const size_t end = s.find(';', i);
      if (end == std::string_view::npos) fail("'&' without ';'");
      const std::string_view entity = s.substr(i + 1, end - i - 1);
      static const std::map<std::string_view, char> named = {
          {"lt", '<'}, {"gt", '>'}, {"amp", '&'}, {"quot", '"'}, {"apos", '\''}};
      if (const auto it = named.find(entity); it != named.end()) {
        out += it->second;
      } else if (entity.size() > 1 && entity[0] == '#') {
        out += character(entity.substr(1));
      } else {
        fail("unknown entity &" + std::string(entity) + ";");
      }
      i = end;
    }
    return out;
  }
  // "&#65;" or "&#x41;" (given without "&#" and ";"): the character, UTF-8 encoded.
  std::string character(std::string_view digits) {
    const bool hex = !digits.empty() && (digits[0] == 'x' || digits[0] == 'X');
    const std::string_view number = hex ? digits.substr(1) : digits;
    bool valid = !number.empty() && number.size() <= 8;  // no overflow below
    unsigned long code = 0;
    for (const char c : number) {
      const int d = std::isdigit(static_cast<unsigned char>(c))           ? c - '0'
                    : hex && std::isxdigit(static_cast<unsigned char>(c)) ? std::tolower(c) - 'a' + 10
                                                                          : -1;
      valid = valid && d >= 0;
      code = code * (hex ? 16 : 10) + (d >= 0 ? d : 0);
    }
    if (!valid || code == 0 || code > 0x10FFFF) fail("'&#" + std::string(digits) + ";' is not a character");
    if (code < 0x80) return std::string(1, static_cast<char>(code));
    const int more = code < 0x800 ? 1 : code < 0x10000 ? 2 : 3;  // continuation bytes
    static constexpr unsigned char kLead[] = {0, 0xC0, 0xE0, 0xF0};
    std::string utf8(1, static_cast<char>(kLead[more] | (code >> (6 * more))));
    for (int k = more - 1; k >= 0; --k) utf8 += static_cast<char>(0x80 | ((code >> (6 * k)) & 0x3F));
    return utf8;
  }
  // FEBio files nest a few levels; recursion this deep is a damaged or hostile file, and would overflow the stack.
  static constexpr int kMaxDepth = 100;

  XmlElement element(int depth = 0) {
    if (depth >= kMaxDepth) fail("elements nested more than " + std::to_string(kMaxDepth) + " deep");
    XmlElement e;
    e.line = line();
    ++pos_;  // '<'
    e.name = name();
    while (true) {
      skip_space();
      if (starts_with("/>")) {
        pos_ += 2;
        return e;
      }
      if (starts_with(">")) {
        ++pos_;
        break;
      }
      const std::string key = name();
      skip_space();
      if (!starts_with("=")) fail("attribute " + key + " without a value");
      ++pos_;
      skip_space();
      const char quote = pos_ < text_.size() ? text_[pos_] : '\0';
      if (quote != '"' && quote != '\'') fail("attribute " + key + ": value not quoted");
      const size_t end = text_.find(quote, pos_ + 1);
      if (end == std::string::npos) fail("attribute " + key + ": value not closed");
      e.attributes[key] = decode(std::string_view(text_).substr(pos_ + 1, end - pos_ - 1));
      pos_ = end + 1;
    }
    while (true) {
      const size_t lt = text_.find('<', pos_);
      if (lt == std::string::npos) fail("element <" + e.name + "> is not closed");
      e.text += decode(std::string_view(text_).substr(pos_, lt - pos_));
      pos_ = lt;
      if (starts_with("</")) {
        pos_ += 2;
        if (name() != e.name) fail("mismatched end tag, expected </" + e.name + ">");
        skip_space();
        if (!starts_with(">")) fail("malformed end tag </" + e.name);
        ++pos_;
        return e;
      }
      if (starts_with("<![CDATA[")) {
        const size_t start = pos_ + 9;
        skip_past("]]>");
        e.text += text_.substr(start, pos_ - 3 - start);
      } else if (starts_with("<!--") || starts_with("<?")) {
        skip_misc();
      } else {
        e.children.push_back(element(depth + 1));
      }
    }
  }

  std::string path_;
  std::string text_;
  size_t pos_ = 0;
  size_t counted_ = 0;  // newlines before counted_ are in line_
  int line_ = 1;
};

// ---- Reading

class FebioReader {
 public:
  explicit FebioReader(const std::string& path) : path_(path) {}

  VolumeMesh read() {
    const XmlElement root = XmlParser(path_).parse();
    if (root.name != "febio_spec") fail(root, "not an FEBio file: the root element is <" + root.name + ">");
    const std::string version = attribute(root, "version");
    if (version != "4.0") fail(root, "febio_spec version " + version + " is not supported (4.0 is)");
    const XmlElement* mesh = nullptr;
    for (const XmlElement& section : root.children) {
      if (section.name == "Mesh") mesh = &section;
      if (section.name == "MeshData") read_mesh_data(section);
    }
    if (!mesh) fail(root, "no <Mesh> section");
    for (const XmlElement& e : mesh->children) {
      if (e.name == "Nodes") {
        for (const XmlElement& n : e.children) add_node(n);
      } else if (e.name == "Elements") {
        read_elements(e);
      } else if (e.name == "NodeSet") {
        node_sets_[attribute(e, "name")] = integers(e, e.text);
      }
    }
    return build(root);
  }

 private:
  struct Element {
    long id;
    CellType type;
    std::string part;
    int line;
    std::vector<long> nodes;  // FEBio order, node ids
  };

  [[noreturn]] void fail(const XmlElement& e, const std::string& problem) const {
    throw Error(path_, problem + ", line " + std::to_string(e.line));
  }

  const std::string& attribute(const XmlElement& e, const std::string& key) const {
    const auto it = e.attributes.find(key);
    if (it == e.attributes.end()) fail(e, "<" + e.name + "> without the attribute " + key);
    return it->second;
  }

  // Comma- (and blank-) separated values.
  std::vector<std::string> values(const std::string& text) const {
    std::string spaced = text;
    std::replace(spaced.begin(), spaced.end(), ',', ' ');
    std::vector<std::string> out;
    for (std::string_view f : split_fields(spaced)) out.emplace_back(f);
    return out;
  }
  std::vector<long> integers(const XmlElement& e, const std::string& text) const {
    std::vector<long> out;
    for (const std::string& f : values(text)) {
      long x;
      if (!parse_integer(f, &x)) fail(e, "<" + e.name + ">: expected integers, found '" + f + "'");
      out.push_back(x);
    }
    return out;
  }
  Eigen::Vector3d vector3(const XmlElement& e) const {
    const std::vector<std::string> f = values(e.text);
    Eigen::Vector3d v;
    if (f.size() != 3) fail(e, "<" + e.name + ">: expected 3 numbers, found " + std::to_string(f.size()));
    for (int k = 0; k < 3; ++k)
      if (!parse_real(f[k], &v(k))) fail(e, "<" + e.name + ">: expected a finite number, found '" + f[k] + "'");
    return v;
  }
  long id(const XmlElement& e) const {
    long x;
    if (!parse_integer(attribute(e, "id"), &x)) fail(e, "<" + e.name + ">: id is not an integer");
    return x;
  }

  void add_node(const XmlElement& n) {
    if (n.name != "node") fail(n, "expected <node> in <Nodes>, found <" + n.name + ">");
    const Eigen::Vector3d x = vector3(n);
    if (!node_index_.emplace(id(n), static_cast<int>(coords_.size() / 3)).second) {
      fail(n, "node " + std::to_string(id(n)) + " defined twice");
    }
    coords_.insert(coords_.end(), {x(0), x(1), x(2)});
  }

  void read_elements(const XmlElement& part) {
    const std::string& type_name = attribute(part, "type");
    CellType type;
    if (type_name == "hex8") {
      type = CellType::Hex;
    } else if (type_name == "penta6") {
      type = CellType::Wedge;
    } else if (type_name == "tet4") {
      type = CellType::Tet;
    } else {
      fail(part, "unsupported element type " + type_name + " (hex8, penta6 and tet4 are supported)");
    }
    const std::string& name = attribute(part, "name");
    for (const XmlElement& e : part.children) {
      if (e.name != "elem") fail(e, "expected <elem> in <Elements>, found <" + e.name + ">");
      std::vector<long> nodes = integers(e, e.text);
      if (static_cast<int>(nodes.size()) != node_count(type)) {
        fail(e, type_name + " element needs " + std::to_string(node_count(type)) + " nodes, found " +
                    std::to_string(nodes.size()));
      }
      parts_[name].push_back(id(e));
      elements_.push_back({id(e), type, name, e.line, std::move(nodes)});
    }
  }

  // mat_axis data refers to elements of a part by their position in it ("lid"), resolved in build().
  void read_mesh_data(const XmlElement& section) {
    for (const XmlElement& data : section.children) {
      if (data.name != "ElementData" || data.attributes.count("type") == 0 || data.attributes.at("type") != "mat_axis")
        continue;
      for (const XmlElement& e : data.children) {
        Eigen::Vector3d a = Eigen::Vector3d::Zero(), d = Eigen::Vector3d::Zero();
        for (const XmlElement& v : e.children) {
          if (v.name != "a" && v.name != "d") fail(v, "mat_axis: expected <a> and <d>, found <" + v.name + ">");
          (v.name == "a" ? a : d) = vector3(v);
        }
        const Eigen::Vector3d normal = a.cross(d);
        if (!(normal.norm() > 1e-12 * a.norm() * d.norm())) fail(e, "mat_axis: a and d are parallel or missing");
        Eigen::Matrix3d frame;
        frame.col(0) = a.normalized();
        frame.col(2) = normal.normalized();
        frame.col(1) = frame.col(2).cross(frame.col(0));
        long lid;
        if (!parse_integer(attribute(e, "lid"), &lid)) fail(e, "mat_axis: lid is not an integer");
        axes_.push_back({attribute(data, "elem_set"), lid, e.line, frame});
      }
    }
  }

  int node(long id, const Element& e) const {
    const auto it = node_index_.find(id);
    if (it == node_index_.end()) {
      throw Error(path_, "element " + std::to_string(e.id) + " refers to unknown node " + std::to_string(id) +
                             ", line " + std::to_string(e.line));
    }
    return it->second;
  }

  VolumeMesh build(const XmlElement& root) {
    if (elements_.empty()) fail(root, "no elements (<Elements type=\"hex8\">, penta6 or tet4)");
    std::stable_sort(elements_.begin(), elements_.end(),
                     [](const Element& a, const Element& b) { return a.id < b.id; });
    VolumeMesh mesh;
    mesh.V = rows_to_matrix(coords_, 3);
    CellBuilder cells;
    std::unordered_map<long, int> cell_of;
    for (const Element& e : elements_) {
      if (!cell_of.emplace(e.id, cells.size()).second) {
        throw Error(path_, "element " + std::to_string(e.id) + " defined twice, line " + std::to_string(e.line));
      }
      int vtk[8];
      for (int k = 0; k < node_count(e.type); ++k) vtk[solver_node(e.type, k)] = node(e.nodes[k], e);
      if (find_repeated(vtk, node_count(e.type)) >= 0) {
        throw Error(path_, "element " + std::to_string(e.id) + " uses a node twice, line " + std::to_string(e.line));
      }
      cells.add(e.type, vtk);
    }
    cells.finish(&mesh);

    std::map<std::string, std::vector<int>> sets;
    for (const auto& [name, ids] : node_sets_)
      for (long id : ids) {
        const auto it = node_index_.find(id);
        if (it == node_index_.end())
          throw Error(path_, "node set " + name + " refers to unknown node " + std::to_string(id));
        sets[name].push_back(it->second);
      }
    if (auto mask = side_mask_from_node_sets(mesh.num_vertices(), sets)) mesh.point_data[kSideMaskArray] = *mask;

    if (!axes_.empty()) {
      const int nc = mesh.num_cells();
      MaterialFrames frames{Eigen::MatrixXd(nc, 3), Eigen::MatrixXd(nc, 3), Eigen::MatrixXd(nc, 3), {}};
      frames.e1.rowwise() = Eigen::RowVector3d::UnitX();
      frames.e2.rowwise() = Eigen::RowVector3d::UnitY();
      frames.e3.rowwise() = Eigen::RowVector3d::UnitZ();
      for (const Axis& axis : axes_) {
        const auto part = parts_.find(axis.part);
        if (part == parts_.end() || axis.lid < 1 || axis.lid > static_cast<long>(part->second.size())) {
          throw Error(path_, "mat_axis lid " + std::to_string(axis.lid) + " is not an element of part '" + axis.part +
                                 "', line " + std::to_string(axis.line));
        }
        const int c = cell_of.at(part->second[axis.lid - 1]);
        frames.e1.row(c) = axis.frame.col(0).transpose();
        frames.e2.row(c) = axis.frame.col(1).transpose();
        frames.e3.row(c) = axis.frame.col(2).transpose();
      }
      attach_frames(mesh, frames);
    }
    check_volume_mesh(path_, mesh);
    return mesh;
  }

  struct Axis {
    std::string part;
    long lid;
    int line;
    Eigen::Matrix3d frame;
  };

  std::string path_;
  std::vector<double> coords_;
  std::unordered_map<long, int> node_index_;
  std::vector<Element> elements_;
  std::map<std::string, std::vector<long>> parts_;  // part name -> element ids in file order
  std::map<std::string, std::vector<long>> node_sets_;
  std::vector<Axis> axes_;
};

// ---- Writing

// Ids as "1,2,3" (1-based).
std::string id_list(const std::vector<int>& zero_based) {
  std::string s;
  for (size_t i = 0; i < zero_based.size(); ++i) s += (i ? "," : "") + std::to_string(zero_based[i] + 1);
  return s;
}

std::string vector_text(const Eigen::RowVector3d& v) {
  return format_double(v(0)) + "," + format_double(v(1)) + "," + format_double(v(2));
}

}  // namespace

VolumeMesh read_febio(const std::string& path) { return FebioReader(path).read(); }

void write_febio(const std::string& file, const VolumeMesh& mesh) {
  const SideSets sets = side_sets(mesh);
  const std::optional<MaterialFrames> frames = export_frames(mesh);
  const std::vector<CellType> types = cell_types_present(mesh);
  std::ofstream out(file);
  if (!out) throw Error(file, "cannot open for writing");

  out << "<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?>\n"
      << "<!-- FaceHex " << FACEHEX_VERSION << " mesh: " << mesh.num_vertices() << " nodes, " << mesh.num_cells()
      << " elements; units mm, N, MPa. Material and boundary conditions are placeholders (docs/export.md). -->\n"
      << "<febio_spec version=\"4.0\">\n"
      << "  <Module type=\"solid\"/>\n"
      << "  <Control>\n    <analysis>STATIC</analysis>\n    <time_steps>10</time_steps>\n"
      << "    <step_size>0.1</step_size>\n  </Control>\n"
      << "  <Material>\n"
      << "    <material id=\"1\" name=\"" << kMaterial << "\" type=\"neo-Hookean\">\n"
      << "      <density>1e-09</density>\n      <E>0.015</E>\n      <v>0.45</v>\n    </material>\n"
      << "  </Material>\n";

  out << "  <Mesh>\n    <Nodes name=\"FaceHex\">\n";
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    out << "      <node id=\"" << i + 1 << "\">" << vector_text(mesh.V.row(i)) << "</node>\n";
  }
  out << "    </Nodes>\n";
  for (CellType t : types) {
    out << "    <Elements type=\"" << febio_type(t) << "\" name=\"" << element_set_name(t) << "\">\n";
    for (int c : cells_of_type(mesh, t)) {
      out << "      <elem id=\"" << c + 1 << "\">";
      for (int k = 0; k < node_count(t); ++k) out << (k ? "," : "") << mesh.C(c, solver_node(t, k)) + 1;
      out << "</elem>\n";
    }
    out << "    </Elements>\n";
  }
  for (int s = 0; s < kNumSides; ++s) {
    if (sets.nodes[s].empty()) continue;
    out << "    <NodeSet name=\"" << kSideSetNames[s] << "\">" << id_list(sets.nodes[s]) << "</NodeSet>\n";
  }
  for (int s = 0; s < kNumSides; ++s) {
    if (sets.faces[s].empty()) continue;
    out << "    <Surface name=\"" << kSideSetNames[s] << kSurfaceSuffix << "\">\n";
    int facet = 0;
    for (const CellFace& cf : sets.faces[s]) {
      const std::vector<int> v = face_vertices(mesh, cf.cell, cf.face);
      const char* tag = v.size() == 4 ? "quad4" : "tri3";
      out << "      <" << tag << " id=\"" << ++facet << "\">" << id_list(v) << "</" << tag << ">\n";
    }
    out << "    </Surface>\n";
  }
  std::vector<int> all(mesh.num_cells());
  for (int c = 0; c < mesh.num_cells(); ++c) all[c] = c;
  out << "    <ElementSet name=\"" << kAllElementsSet << "\">" << id_list(all) << "</ElementSet>\n  </Mesh>\n";

  out << "  <MeshDomains>\n";
  for (CellType t : types)
    out << "    <SolidDomain name=\"" << element_set_name(t) << "\" mat=\"" << kMaterial << "\"/>\n";
  out << "  </MeshDomains>\n";
  if (frames) {
    out << "  <MeshData>\n";
    for (CellType t : types) {
      out << "    <ElementData type=\"mat_axis\" elem_set=\"" << element_set_name(t) << "\">\n";
      int lid = 0;
      for (int c : cells_of_type(mesh, t)) {
        out << "      <elem lid=\"" << ++lid << "\"><a>" << vector_text(frames->e1.row(c)) << "</a><d>"
            << vector_text(frames->e2.row(c)) << "</d></elem>\n";
      }
      out << "    </ElementData>\n";
    }
    out << "  </MeshData>\n";
  }
  if (!sets.nodes[W0].empty()) {
    out << "  <Boundary>\n    <bc name=\"fixed_bone\" node_set=\"" << kSideSetNames[W0]
        << "\" type=\"zero displacement\">\n"
        << "      <x_dof>1</x_dof>\n      <y_dof>1</y_dof>\n      <z_dof>1</z_dof>\n    </bc>\n  </Boundary>\n";
  }
  out << "  <Output>\n    <plotfile type=\"febio\">\n      <var type=\"displacement\"/>\n"
      << "      <var type=\"stress\"/>\n    </plotfile>\n  </Output>\n</febio_spec>\n";
  out.flush();
  if (!out) throw Error(file, "write failed (disk full?)");
}

}  // namespace facehex::io
