#include "core/io/abaqus_io.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <unordered_map>

#include "core/io/fe_sets.h"
#include "core/io/io_util.h"
#include "core/mesh/cell_faces.h"
#include "core/util/error.h"

namespace facehex::io {

namespace {

constexpr const char* kMaterial = "SOFT_TISSUE";
constexpr const char* kDistribution = "FRAMES";
constexpr const char* kOrientation = "FRAME";
constexpr int kIdsPerLine = 16;                        // the Abaqus limit for data lines of *NSET and *ELSET
constexpr std::string_view kHeadingSizes = " mesh: ";  // in the heading, before the sizes

const char* abaqus_type(CellType type) {
  switch (type) {
    case CellType::Hex:
      return "C3D8";
    case CellType::Wedge:
      return "C3D6";
    case CellType::Tet:
      return "C3D4";
  }
  return "";
}

// Face node lists of the Abaqus manual (1-based Abaqus node numbers), index i = face S(i+1).
const std::vector<std::vector<int>>& manual_faces(CellType type) {
  static const std::vector<std::vector<int>> hex = {{1, 2, 3, 4}, {5, 8, 7, 6}, {1, 5, 6, 2},
                                                    {2, 6, 7, 3}, {3, 7, 8, 4}, {4, 8, 5, 1}};
  static const std::vector<std::vector<int>> wedge = {{1, 2, 3}, {4, 6, 5}, {1, 4, 5, 2}, {2, 5, 6, 3}, {3, 6, 4, 1}};
  static const std::vector<std::vector<int>> tet = {{1, 2, 3}, {1, 4, 2}, {2, 4, 3}, {3, 4, 1}};
  return type == CellType::Hex ? hex : type == CellType::Wedge ? wedge : tet;
}

// CalculiX reads at most 20 characters per field: the shortest text that reads back to exactly x, else (only for
// 17-digit values with an exponent) the most digits that fit, which is still 13 or more.
std::string format_field(double x) {
  char buf[32];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, x);
    if (std::strtod(buf, nullptr) == x) break;
  }
  for (int digits = 16; std::strlen(buf) > 20; --digits) std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

// Frame vectors are unit vectors: 9 digits keep them exact to 1e-9 and the line under CalculiX's 132 characters.
std::string format_unit(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", x);
  return buf;
}

void write_ids(std::ofstream& out, const std::vector<int>& zero_based) {
  for (size_t i = 0; i < zero_based.size(); ++i) {
    out << zero_based[i] + 1 << ((i + 1) % kIdsPerLine == 0 || i + 1 == zero_based.size() ? "\n" : ", ");
  }
}

std::string upper(std::string_view s) {
  std::string u(s);
  std::transform(u.begin(), u.end(), u.begin(), [](unsigned char c) { return std::toupper(c); });
  return u;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// Comma-separated fields, trimmed; a trailing comma (a continued line) adds no empty field.
std::vector<std::string_view> comma_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    fields.push_back(
        trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (fields.size() > 1 && fields.back().empty()) fields.pop_back();
  return fields;
}

bool is_comment(std::string_view line) { return trim(line).substr(0, 2) == "**"; }
bool is_keyword(std::string_view line) { return !trim(line).empty() && trim(line)[0] == '*'; }

struct Keyword {
  std::string name;                           // upper case, without '*'
  std::map<std::string, std::string> params;  // upper-case keys and values; "" for flags
};

Keyword parse_keyword(std::string_view line) {
  const std::vector<std::string_view> fields = comma_fields(trim(line).substr(1));
  Keyword kw{upper(fields[0]), {}};
  for (size_t i = 1; i < fields.size(); ++i) {
    const size_t eq = fields[i].find('=');
    if (eq == std::string_view::npos) {
      kw.params[upper(fields[i])] = "";
    } else {
      kw.params[upper(trim(fields[i].substr(0, eq)))] = upper(trim(fields[i].substr(eq + 1)));
    }
  }
  return kw;
}

class AbaqusReader {
 public:
  explicit AbaqusReader(const std::string& path) : in_(path) {}

  VolumeMesh read() {
    bool more = advance();
    while (more) {
      if (!is_keyword(in_.line())) in_.fail("expected a keyword line (*NODE, *ELEMENT, ...), found data");
      const Keyword kw = parse_keyword(in_.line());
      if (kw.name == "INCLUDE") in_.fail("*INCLUDE is not supported: merge the included file into this one");
      more = advance();
      if (kw.name == "NODE") {
        for (; more && !is_keyword(in_.line()); more = advance()) add_node();
      } else if (kw.name == "ELEMENT") {
        more = read_elements(kw);
      } else if (kw.name == "NSET") {
        more = read_node_set(kw);
      } else if (kw.name == "DISTRIBUTION") {
        more = read_distribution();
      } else if (kw.name == "HEADING") {
        more = read_heading();
      } else {
        if (kw.name == "SOLID SECTION") saw_solid_section_ = true;
        while (more && !is_keyword(in_.line())) more = advance();
      }
    }
    check_declared_sizes();
    return build();
  }

 private:
  struct Element {
    long id;
    CellType type;
    int line;
    std::vector<long> nodes;  // Abaqus order, node ids
  };

  bool advance() {
    while (in_.next())
      if (!is_comment(in_.line())) return true;
    return false;
  }

  std::vector<std::string_view> fields() const { return comma_fields(in_.line()); }

  long integer(std::string_view field, const std::string& what) const {
    long x;
    if (!parse_integer(field, &x)) in_.fail("expected an integer " + what + ", found '" + std::string(field) + "'");
    return x;
  }

  double real(std::string_view field, const std::string& what) const {
    double x;
    if (!parse_real(field, &x))
      in_.fail("expected a finite number for " + what + ", found '" + std::string(field) + "'");
    return x;
  }

  void add_node() {
    const auto f = fields();
    if (f.size() != 4) in_.fail("a node needs 'id, x, y, z' (3-D), found " + std::to_string(f.size()) + " fields");
    const long id = integer(f[0], "node id");
    if (!node_index_.emplace(id, static_cast<int>(coords_.size() / 3)).second) {
      in_.fail("node " + std::to_string(id) + " defined twice");
    }
    for (int k = 1; k <= 3; ++k) coords_.push_back(real(f[k], "a coordinate"));
  }

  CellType element_type(const Keyword& kw) const {
    const auto it = kw.params.find("TYPE");
    if (it == kw.params.end()) in_.fail("*ELEMENT without TYPE=");
    const std::string& t = it->second;
    const bool suffix_ok = t.size() >= 4 && std::all_of(t.begin() + 4, t.end(), [](char c) { return std::isalpha(c); });
    if (suffix_ok && t.compare(0, 4, "C3D8") == 0) return CellType::Hex;
    if (suffix_ok && t.compare(0, 4, "C3D6") == 0) return CellType::Wedge;
    if (suffix_ok && t.compare(0, 4, "C3D4") == 0) return CellType::Tet;
    in_.fail("unsupported element type " + t + " (linear solids C3D8*, C3D6*, C3D4* are supported)");
  }

  // An element's data may continue on the next lines (each but the last ending with a comma).
  bool read_elements(const Keyword& kw) {
    const CellType type = element_type(kw);
    const size_t needed = 1 + node_count(type);
    bool more = true;
    Element pending{0, type, 0, {}};
    while (more && !is_keyword(in_.line())) {
      if (pending.id == 0) pending.line = in_.line_number();
      for (std::string_view f : fields()) {
        if (pending.id == 0) {
          pending.id = integer(f, "element id");
          if (pending.id <= 0) in_.fail("element ids must be positive, found " + std::to_string(pending.id));
        } else {
          pending.nodes.push_back(integer(f, "node id"));
        }
      }
      if (pending.nodes.size() + 1 > needed) {
        in_.fail("element " + std::to_string(pending.id) + " of type " + kw.params.at("TYPE") + " needs " +
                 std::to_string(needed - 1) + " nodes, found " + std::to_string(pending.nodes.size()));
      }
      if (pending.nodes.size() + 1 == needed) {
        elements_.push_back(pending);
        pending = Element{0, type, 0, {}};
      }
      more = advance();
    }
    if (pending.id != 0) {
      throw Error(in_.path(),
                  "element " + std::to_string(pending.id) + " is incomplete, line " + std::to_string(pending.line));
    }
    return more;
  }

  bool read_node_set(const Keyword& kw) {
    const auto name = kw.params.find("NSET");
    if (name == kw.params.end()) in_.fail("*NSET without NSET=");
    std::vector<long>& ids = node_sets_[name->second];
    const bool generate = kw.params.count("GENERATE") > 0;
    bool more = true;
    for (; more && !is_keyword(in_.line()); more = advance()) {
      const auto f = fields();
      if (generate) {
        if (f.size() < 2 || f.size() > 3) in_.fail("*NSET, GENERATE needs 'first, last[, step]'");
        const long first = integer(f[0], "first node"), last = integer(f[1], "last node");
        const long step = f.size() == 3 ? integer(f[2], "step") : 1;
        if (step <= 0 || last < first) in_.fail("*NSET, GENERATE needs first <= last and a positive step");
        // Each id generated must be a node defined before: a damaged range would otherwise fill memory.
        if ((last - first) / step >= static_cast<long>(node_index_.size()))
          in_.fail("*NSET, GENERATE covers more ids than the " + std::to_string(node_index_.size()) +
                   " nodes defined before it");
        for (long id = first; id <= last; id += step) ids.push_back(id);
        continue;
      }
      for (std::string_view field : f) {
        long id;
        if (parse_integer(field, &id)) {
          ids.push_back(id);
        } else if (const auto other = node_sets_.find(upper(field)); other != node_sets_.end()) {
          ids.insert(ids.end(), other->second.begin(), other->second.end());
        } else {
          in_.fail("unknown node or node set '" + std::string(field) + "'");
        }
      }
    }
    return more;
  }

  // The heading FaceHex writes, "FaceHex VERSION mesh: N nodes, M C3D8, ...; units ...", declares the deck's sizes.
  bool read_heading() {
    bool more = true;
    for (; more && !is_keyword(in_.line()); more = advance()) {
      const std::string_view line = trim(in_.line());
      const size_t at = line.find(kHeadingSizes), end = line.find(';');
      if (line.substr(0, 8) != "FaceHex " || at == std::string_view::npos || end == std::string_view::npos || end < at)
        continue;
      std::map<std::string, long> sizes;
      for (std::string_view item :
           comma_fields(line.substr(at + kHeadingSizes.size(), end - at - kHeadingSizes.size()))) {
        const std::vector<std::string_view> words = split_fields(item);
        long n;
        if (words.size() != 2 || !parse_integer(words[0], &n)) in_.fail("unreadable sizes in the FaceHex heading");
        sizes[std::string(words[1])] = n;
      }
      declared_sizes_ = sizes;
    }
    return more;
  }

  // A deck FaceHex wrote must hold what its heading declares and reach its *SOLID SECTION, the last line written:
  // a copy cut short at a line end would otherwise read as a smaller mesh.
  void check_declared_sizes() const {
    if (!declared_sizes_) return;
    std::map<std::string, long> found = {{"nodes", static_cast<long>(coords_.size() / 3)}};
    for (const Element& e : elements_) ++found[abaqus_type(e.type)];
    const auto describe = [](const std::map<std::string, long>& sizes) {
      std::string s;
      for (const auto& [what, n] : sizes) s += (s.empty() ? "" : ", ") + std::to_string(n) + " " + what;
      return s;
    };
    if (found != *declared_sizes_) {
      throw Error(in_.path(), "holds " + describe(found) + " where its FaceHex heading declares " +
                                  describe(*declared_sizes_) + ": the file was cut short or edited");
    }
    if (!saw_solid_section_) {
      throw Error(in_.path(), "ends before its *SOLID SECTION, the last line FaceHex writes: the file was cut short");
    }
  }

  // "*DISTRIBUTION": a default line ", a, b", then "element, a, b" lines; a and b span the local 1-2 plane.
  bool read_distribution() {
    if (have_distribution_) in_.fail("more than one *DISTRIBUTION (only one frame per element is supported)");
    have_distribution_ = true;
    bool more = true;
    bool first = true;
    for (; more && !is_keyword(in_.line()); more = advance(), first = false) {
      const auto f = fields();
      if (f.size() != 7) in_.fail("a distribution line needs 'element, a1, a2, a3, b1, b2, b3'");
      Eigen::Vector3d a, b;
      for (int k = 0; k < 3; ++k) {
        a(k) = real(f[1 + k], "a");
        b(k) = real(f[4 + k], "b");
      }
      const Eigen::Vector3d normal = a.cross(b);
      if (!(normal.norm() > 1e-12 * a.norm() * b.norm())) in_.fail("points a and b are parallel");
      Eigen::Matrix3d frame;
      frame.col(0) = a.normalized();
      frame.col(2) = normal.normalized();
      frame.col(1) = frame.col(2).cross(frame.col(0));
      if (first) {
        if (!f[0].empty()) in_.fail("the first line of *DISTRIBUTION is the default and starts with an empty field");
        default_frame_ = frame;
      } else {
        frames_[integer(f[0], "element id")] = frame;
      }
    }
    return more;
  }

  int node(long id, const std::string& user) const {
    const auto it = node_index_.find(id);
    if (it == node_index_.end()) throw Error(in_.path(), user + " refers to unknown node " + std::to_string(id));
    return it->second;
  }

  VolumeMesh build() {
    if (elements_.empty()) throw Error(in_.path(), "no solid elements (*ELEMENT, TYPE=C3D8/C3D6/C3D4)");
    std::stable_sort(elements_.begin(), elements_.end(),
                     [](const Element& a, const Element& b) { return a.id < b.id; });
    VolumeMesh mesh;
    mesh.V = rows_to_matrix(coords_, 3);
    CellBuilder cells;
    for (size_t i = 0; i < elements_.size(); ++i) {
      const Element& e = elements_[i];
      if (i > 0 && e.id == elements_[i - 1].id) {
        throw Error(in_.path(), "element " + std::to_string(e.id) + " defined twice");
      }
      const std::string user = "element " + std::to_string(e.id) + " (line " + std::to_string(e.line) + ")";
      int vtk[8];
      for (int k = 0; k < node_count(e.type); ++k) vtk[solver_node(e.type, k)] = node(e.nodes[k], user);
      if (const int k = find_repeated(vtk, node_count(e.type)); k >= 0) {
        throw Error(in_.path(), user + " uses node " + std::to_string(e.nodes[solver_node(e.type, k)]) + " twice");
      }
      cells.add(e.type, vtk);
    }
    cells.finish(&mesh);

    std::map<std::string, std::vector<int>> sets;
    for (const auto& [name, ids] : node_sets_)
      for (long id : ids) sets[name].push_back(node(id, "node set " + name));
    if (auto mask = side_mask_from_node_sets(mesh.num_vertices(), sets)) mesh.point_data[kSideMaskArray] = *mask;

    if (have_distribution_) {
      MaterialFrames frames{Eigen::MatrixXd(elements_.size(), 3),
                            Eigen::MatrixXd(elements_.size(), 3),
                            Eigen::MatrixXd(elements_.size(), 3),
                            {}};
      for (size_t i = 0; i < elements_.size(); ++i) {
        const auto it = frames_.find(elements_[i].id);
        const Eigen::Matrix3d& frame = it == frames_.end() ? default_frame_ : it->second;
        frames.e1.row(i) = frame.col(0).transpose();
        frames.e2.row(i) = frame.col(1).transpose();
        frames.e3.row(i) = frame.col(2).transpose();
      }
      attach_frames(mesh, frames);
    }
    check_volume_mesh(in_.path(), mesh);
    return mesh;
  }

  LineParser in_;
  std::vector<double> coords_;
  std::unordered_map<long, int> node_index_;
  std::vector<Element> elements_;
  std::map<std::string, std::vector<long>> node_sets_;
  std::optional<std::map<std::string, long>> declared_sizes_;  // "nodes", "C3D8", ... from a FaceHex heading
  bool saw_solid_section_ = false;
  bool have_distribution_ = false;
  Eigen::Matrix3d default_frame_ = Eigen::Matrix3d::Identity();
  std::map<long, Eigen::Matrix3d> frames_;
};

}  // namespace

int abaqus_face(CellType type, int vtk_face) {
  const LocalFace& face = cell_faces(type)[vtk_face];
  std::vector<int> nodes;
  for (int k = 0; k < face.size; ++k) nodes.push_back(solver_node(type, face.node[k]) + 1);
  std::sort(nodes.begin(), nodes.end());
  const auto& faces = manual_faces(type);
  for (size_t i = 0; i < faces.size(); ++i) {
    std::vector<int> manual = faces[i];
    std::sort(manual.begin(), manual.end());
    if (manual == nodes) return static_cast<int>(i) + 1;
  }
  throw Error("abaqus_face", "no Abaqus face matches");  // unreachable: both tables list every face
}

VolumeMesh read_abaqus(const std::string& path) { return AbaqusReader(path).read(); }

void write_abaqus(const std::string& file, const VolumeMesh& mesh) {
  const SideSets sets = side_sets(mesh);
  const std::optional<MaterialFrames> frames = export_frames(mesh);
  const std::vector<CellType> types = cell_types_present(mesh);
  std::ofstream out(file);
  if (!out) throw Error(file, "cannot open for writing");

  out << "*HEADING\nFaceHex " << FACEHEX_VERSION << kHeadingSizes << mesh.num_vertices() << " nodes";
  for (CellType t : types) out << ", " << mesh.count(t) << ' ' << abaqus_type(t);
  out << "; units mm, N, MPa\n"
      << "** The model only: *INCLUDE it in a job that adds the *STEP (docs/export.md).\n"
      << "** Node i+1 = mesh vertex i, element c+1 = mesh cell c.\n";

  out << "*NODE, NSET=NALL\n";
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    out << i + 1 << ", " << format_field(mesh.V(i, 0)) << ", " << format_field(mesh.V(i, 1)) << ", "
        << format_field(mesh.V(i, 2)) << '\n';
  }
  for (CellType t : types) {
    out << "*ELEMENT, TYPE=" << abaqus_type(t) << ", ELSET=" << element_set_name(t) << '\n';
    for (int c : cells_of_type(mesh, t)) {
      out << c + 1;
      for (int k = 0; k < node_count(t); ++k) out << ", " << mesh.C(c, solver_node(t, k)) + 1;
      out << '\n';
    }
  }
  out << "*ELSET, ELSET=" << kAllElementsSet << '\n';
  for (size_t i = 0; i < types.size(); ++i) out << (i ? ", " : "") << element_set_name(types[i]);
  out << '\n';

  for (int s = 0; s < kNumSides; ++s) {
    if (sets.nodes[s].empty()) continue;
    out << "** side " << kSideNames[s] << ": " << kSideDescriptions[s] << "\n*NSET, NSET=" << kSideSetNames[s] << '\n';
    write_ids(out, sets.nodes[s]);
    if (sets.faces[s].empty()) continue;
    out << "*SURFACE, TYPE=ELEMENT, NAME=" << kSideSetNames[s] << kSurfaceSuffix << '\n';
    for (const CellFace& cf : sets.faces[s]) {
      out << cf.cell + 1 << ", S" << abaqus_face(mesh.types[cf.cell], cf.face) << '\n';
    }
  }

  if (frames) {
    out << "** Material frame per element (docs/export.md): a = e1 (lateral), b = e2 (up); local 3 = e3 (depth)\n"
        << "*DISTRIBUTION, NAME=" << kDistribution << ", LOCATION=ELEMENT\n, 1., 0., 0., 0., 1., 0.\n";
    for (int c = 0; c < mesh.num_cells(); ++c) {
      out << c + 1;
      for (int k = 0; k < 3; ++k) out << ", " << format_unit(frames->e1(c, k));
      for (int k = 0; k < 3; ++k) out << ", " << format_unit(frames->e2(c, k));
      out << '\n';
    }
    out << "*ORIENTATION, NAME=" << kOrientation << ", SYSTEM=RECTANGULAR\n" << kDistribution << '\n';
  }
  out << "** Placeholder material, replace it: isotropic linear elastic soft tissue, E = 15 kPa, nu = 0.45.\n"
      << "** Anisotropic *ELASTIC constants refer to the local axes 1, 2, 3 = e1, e2, e3 of the orientation.\n"
      << "*MATERIAL, NAME=" << kMaterial << "\n*ELASTIC\n0.015, 0.45\n"
      << "*SOLID SECTION, ELSET=" << kAllElementsSet << ", MATERIAL=" << kMaterial
      << (frames ? std::string(", ORIENTATION=") + kOrientation : std::string()) << '\n';
  out.flush();
  if (!out) throw Error(file, "write failed (disk full?)");
}

}  // namespace facehex::io
