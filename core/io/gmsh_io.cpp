#include "core/io/gmsh_io.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <unordered_map>
#include <vector>

#include "core/io/fe_sets.h"
#include "core/io/io_util.h"
#include "core/mesh/cell_faces.h"
#include "core/util/error.h"

namespace facehex::io {

namespace {

// Gmsh numbers a prism's bottom triangle so that its right-hand normal points towards the top one; VTK's wedge has
// it point away. Swapping nodes 1<->2 and 4<->5 converts between the two (in both directions).
constexpr int kPrismToWedge[6] = {0, 2, 1, 3, 5, 4};

// Dimension of the Gmsh element types we may meet (-1: unknown). Lower-dimensional elements are skipped, so this is
// all we need to know about them; of the volume types only 4, 5 and 6 are read.
int element_dimension(long type) {
  static const std::map<long, int> kDimension = {
      {15, 0}, {1, 1},  {8, 1},  {26, 1}, {27, 1}, {28, 1}, {2, 2},  {3, 2},  {9, 2},  {10, 2}, {16, 2},
      {20, 2}, {21, 2}, {22, 2}, {23, 2}, {24, 2}, {25, 2}, {4, 3},  {5, 3},  {6, 3},  {7, 3},  {11, 3},
      {12, 3}, {13, 3}, {14, 3}, {17, 3}, {18, 3}, {19, 3}, {29, 3}, {30, 3}, {31, 3}, {92, 3}, {93, 3}};
  const auto it = kDimension.find(type);
  return it == kDimension.end() ? -1 : it->second;
}

bool volume_cell_type(long gmsh_type, CellType* type) {
  if (gmsh_type < 4 || gmsh_type > 6) return false;
  *type = gmsh_type == 4 ? CellType::Tet : gmsh_type == 5 ? CellType::Hex : CellType::Wedge;
  return true;
}

int gmsh_type_code(CellType t) { return t == CellType::Tet ? 4 : t == CellType::Hex ? 5 : 6; }

class GmshReader {
 public:
  explicit GmshReader(const std::string& path) : in_(path) {}

  VolumeMesh read() {
    read_format();
    bool have_nodes = false, have_elements = false;
    while (in_.next()) {
      const std::string section(in_.field(0));
      if (section[0] != '$') {
        in_.fail("expected a section ($Nodes, $Elements, ...), found '" + std::string(in_.line().substr(0, 40)) + "'");
      }
      if (section == "$Nodes") {
        if (have_nodes) in_.fail("second $Nodes section");
        version_ == 4 ? read_nodes_v4() : read_nodes_v2();
        have_nodes = true;
      } else if (section == "$Elements") {
        if (!have_nodes) in_.fail("$Elements before $Nodes");
        if (have_elements) in_.fail("second $Elements section");
        version_ == 4 ? read_elements_v4() : read_elements_v2();
        have_elements = true;
      } else if (section == "$Entities" && version_ == 4) {
        read_entities();
      } else {
        skip_section(section);
      }
    }
    if (!have_nodes) throw Error(in_.path(), "no $Nodes section");
    if (!have_elements) throw Error(in_.path(), "no $Elements section");
    if (cells_.size() == 0) throw Error(in_.path(), "no volume elements (tetrahedra, hexahedra or prisms)");
    VolumeMesh mesh;
    mesh.V = rows_to_matrix(coords_, 3);
    cells_.finish(&mesh);
    if (any_physical_) mesh.cell_data["gmsh_physical"] = rows_to_matrix(physical_, 1);
    check_volume_mesh(in_.path(), mesh);
    return mesh;
  }

 private:
  void read_format() {
    in_.require_next("$MeshFormat");
    if (in_.field(0) == "$NOD") in_.fail("Gmsh format 1.0 is not supported (2.2 and 4.1 are)");
    if (in_.field(0) != "$MeshFormat") in_.fail("not a Gmsh file: it does not start with $MeshFormat");
    in_.require_next("'<version> <file-type> <data-size>'");
    in_.require_fields(3, "the mesh format");
    const double version = in_.real(0, "the format version");
    if (in_.integer(1, "the file type") != 0) in_.fail("binary .msh not supported: save the mesh as ASCII");
    if (version >= 2.0 && version < 3.0) {
      version_ = 2;
    } else if (std::fabs(version - 4.1) < 1e-9) {
      version_ = 4;
    } else {
      in_.fail("Gmsh format version " + std::string(in_.field(0)) + " is not supported (2.2 and 4.1 are)");
    }
    expect_line("$EndMeshFormat");
  }

  void expect_line(const std::string& marker) {
    in_.require_next(marker);
    if (in_.field(0) == marker) return;
    if (in_.field(0)[0] != '$') in_.fail("more records than the section header announced (expected " + marker + ")");
    in_.fail("expected " + marker + ", found '" + std::string(in_.line().substr(0, 40)) + "'");
  }

  // Next record of a section that announced `count` of them; a '$' line here means the count is wrong.
  void next_record(const std::string& what, long i, long count) {
    in_.require_next(what + " " + std::to_string(i + 1) + " of " + std::to_string(count));
    if (in_.field(0)[0] == '$') {
      in_.fail("section ended after " + std::to_string(i) + " " + what + "s, but " + std::to_string(count) +
               " were announced");
    }
  }

  void skip_section(const std::string& section) {
    const std::string end = "$End" + section.substr(1);
    while (in_.next()) {
      if (in_.field(0) == end) return;
    }
    in_.fail("section " + section + " is not closed by " + end);
  }

  long count_field(size_t i, const std::string& what) {
    const long n = in_.integer(i, what);
    if (n < 0) in_.fail(what + " is negative");
    return n;
  }

  void add_node(long tag, double x, double y, double z) {
    if (!node_index_.emplace(tag, static_cast<int>(coords_.size() / 3)).second) {
      in_.fail("node " + std::to_string(tag) + " defined twice");
    }
    coords_.insert(coords_.end(), {x, y, z});
  }

  void read_nodes_v2() {
    in_.require_next("the number of nodes");
    const long n = count_field(0, "number of nodes");
    for (long i = 0; i < n; ++i) {
      next_record("node", i, n);
      in_.require_fields(4, "a node (tag x y z)");
      add_node(in_.integer(0, "node tag"), in_.real(1, "x"), in_.real(2, "y"), in_.real(3, "z"));
    }
    expect_line("$EndNodes");
  }

  void read_nodes_v4() {
    in_.require_next("'<#blocks> <#nodes> <min tag> <max tag>'");
    in_.require_fields(4, "the $Nodes header");
    const long blocks = count_field(0, "number of node blocks");
    const long n = count_field(1, "number of nodes");
    long read = 0;
    std::vector<long> tags;
    for (long b = 0; b < blocks; ++b) {
      next_record("node block", b, blocks);
      in_.require_fields(4, "a node block header (dim, entity, parametric, count)");
      const long dim = in_.integer(0, "entity dimension");
      const bool parametric = in_.integer(2, "parametric flag") != 0;
      const long m = count_field(3, "number of nodes in the block");
      if (read + m > n) in_.fail("node blocks hold more than the " + std::to_string(n) + " nodes announced");
      tags.clear();
      for (long i = 0; i < m; ++i) {
        next_record("node tag", i, m);
        tags.push_back(in_.integer(0, "node tag"));
      }
      const size_t fields = 3 + (parametric ? static_cast<size_t>(std::max(dim, 0L)) : 0);
      for (long i = 0; i < m; ++i) {
        next_record("node coordinate line", i, m);
        in_.require_fields(fields, "node coordinates");
        add_node(tags[i], in_.real(0, "x"), in_.real(1, "y"), in_.real(2, "z"));
      }
      read += m;
    }
    if (read != n) in_.fail("node blocks hold " + std::to_string(read) + " nodes, " + std::to_string(n) + " announced");
    expect_line("$EndNodes");
  }

  void read_entities() {
    in_.require_next("'<#points> <#curves> <#surfaces> <#volumes>'");
    in_.require_fields(4, "the $Entities header");
    const long lower =
        count_field(0, "number of points") + count_field(1, "number of curves") + count_field(2, "number of surfaces");
    const long volumes = count_field(3, "number of volumes");
    for (long i = 0; i < lower; ++i) next_record("point/curve/surface entity", i, lower);
    for (long i = 0; i < volumes; ++i) {
      next_record("volume entity", i, volumes);
      // tag, bounding box (6), #physical tags, physical tags...
      const long n_physical = count_field(7, "number of physical tags");
      volume_physical_[in_.integer(0, "volume tag")] = n_physical > 0 ? in_.integer(8, "physical tag") : 0;
    }
    expect_line("$EndEntities");
  }

  // Node tags from field `first` on, mapped to 0-based indices, converted to VTK order.
  void add_cell(long gmsh_type, size_t first, long physical) {
    CellType type;
    if (!volume_cell_type(gmsh_type, &type)) {
      in_.fail("unsupported volume element type " + std::to_string(gmsh_type) +
               " (only tetrahedra 4, hexahedra 5 and prisms 6 are supported)");
    }
    const int n = node_count(type);
    if (in_.size() != first + n) {
      in_.fail("element of type " + std::to_string(gmsh_type) + " needs " + std::to_string(n) + " nodes, found " +
               std::to_string(static_cast<long>(in_.size()) - static_cast<long>(first)));
    }
    int gmsh[8], vtk[8];
    for (int k = 0; k < n; ++k) {
      const long tag = in_.integer(first + k, "node tag");
      const auto it = node_index_.find(tag);
      if (it == node_index_.end()) in_.fail("element refers to unknown node " + std::to_string(tag));
      gmsh[k] = it->second;
    }
    if (const int k = find_repeated(gmsh, n); k >= 0) {
      in_.fail("element uses node " + std::string(in_.field(first + k)) + " twice");
    }
    for (int k = 0; k < n; ++k) vtk[k] = type == CellType::Wedge ? gmsh[kPrismToWedge[k]] : gmsh[k];
    cells_.add(type, vtk);
    physical_.push_back(static_cast<double>(physical));
    any_physical_ = any_physical_ || physical != 0;
  }

  long element_type_dimension(long type) {
    const int dim = element_dimension(type);
    if (dim < 0) in_.fail("unknown Gmsh element type " + std::to_string(type));
    return dim;
  }

  void read_elements_v2() {
    in_.require_next("the number of elements");
    const long n = count_field(0, "number of elements");
    for (long i = 0; i < n; ++i) {
      next_record("element", i, n);
      in_.require_fields(3, "an element (tag type #tags ...)");
      const long type = in_.integer(1, "element type");
      if (element_type_dimension(type) < 3) continue;
      const long n_tags = count_field(2, "number of tags");
      const long physical = n_tags > 0 ? in_.integer(3, "physical tag") : 0;
      add_cell(type, 3 + static_cast<size_t>(n_tags), physical);
    }
    expect_line("$EndElements");
  }

  void read_elements_v4() {
    in_.require_next("'<#blocks> <#elements> <min tag> <max tag>'");
    in_.require_fields(4, "the $Elements header");
    const long blocks = count_field(0, "number of element blocks");
    const long n = count_field(1, "number of elements");
    long read = 0;
    for (long b = 0; b < blocks; ++b) {
      next_record("element block", b, blocks);
      in_.require_fields(4, "an element block header (dim, entity, type, count)");
      const long dim = in_.integer(0, "entity dimension");
      const long entity = in_.integer(1, "entity tag");
      const long type = in_.integer(2, "element type");
      const long m = count_field(3, "number of elements in the block");
      if (element_type_dimension(type) != dim) {
        in_.fail("element type " + std::to_string(type) + " in a block of dimension " + std::to_string(dim));
      }
      if (read + m > n) in_.fail("element blocks hold more than the " + std::to_string(n) + " elements announced");
      const auto it = volume_physical_.find(entity);
      const long physical = it == volume_physical_.end() ? 0 : it->second;
      for (long i = 0; i < m; ++i) {
        next_record("element", i, m);
        if (dim == 3) add_cell(type, 1, physical);
      }
      read += m;
    }
    if (read != n) {
      in_.fail("element blocks hold " + std::to_string(read) + " elements, " + std::to_string(n) + " announced");
    }
    expect_line("$EndElements");
  }

  LineParser in_;
  int version_ = 0;
  std::vector<double> coords_;
  std::unordered_map<long, int> node_index_;
  std::map<long, long> volume_physical_;  // 4.1: volume entity tag -> its first physical tag
  CellBuilder cells_;
  std::vector<double> physical_;
  bool any_physical_ = false;
};

}  // namespace

VolumeMesh read_gmsh(const std::string& path) { return GmshReader(path).read(); }

namespace {

// How a mesh is laid out in a Gmsh 4.1 file: physical tags, entities and element blocks.
struct GmshLayout {
  std::vector<long> physical;      // #C, each cell's physical volume tag (0: none)
  std::vector<std::string> names;  // $PhysicalNames lines: dimension tag "name"
  std::vector<int> surfaces;       // sides with faces: surface entity and physical tag s+1
  std::map<long, int> entity_of;   // physical tag -> volume entity tag (1, 2, ...)
  std::map<int, std::pair<Eigen::RowVector3d, Eigen::RowVector3d>> boxes;  // volume entity -> bounding box
  std::vector<std::pair<int, int>> runs;  // element blocks of cells: [first, end), one entity and type each
  struct FaceBlock {
    int side, gmsh_type;
    std::vector<std::vector<int>> faces;
  };
  std::vector<FaceBlock> face_blocks;  // boundary faces after the cells, one block per side and face size
  size_t num_faces = 0;
};

std::vector<long> physical_tags(const std::string& file, const VolumeMesh& mesh) {
  std::vector<long> physical(mesh.num_cells(), 0);
  const auto given = mesh.cell_data.find("gmsh_physical");
  if (given == mesh.cell_data.end()) return physical;
  for (int c = 0; c < mesh.num_cells(); ++c) {
    const double p = given->second(c, 0);
    if (p < 0 || p != std::floor(p)) throw Error(file, "cell data 'gmsh_physical' must hold non-negative integers");
    physical[c] = static_cast<long>(p);
  }
  return physical;
}

GmshLayout gmsh_layout(const std::string& file, const VolumeMesh& mesh, const SideSets& sides) {
  const int nc = mesh.num_cells();
  GmshLayout g;
  // One volume entity per physical tag: in 4.1 physical groups are attached to entities, not to elements.
  g.physical = physical_tags(file, mesh);
  // Side surfaces (fe_sets.h) become physical surfaces s+1 named like the FE exports' surfaces; Gmsh tools keep only
  // elements in physical groups, so the volume then needs one too: physical volume 1 "ALL" unless given.
  for (int s = 0; s < kNumSides; ++s) {
    if (sides.faces[s].empty()) continue;
    g.surfaces.push_back(s);
    g.names.push_back("2 " + std::to_string(s + 1) + " \"" + kSideSetNames[s] + kSurfaceSuffix + "\"");
  }
  if (!g.surfaces.empty() && !mesh.cell_data.count("gmsh_physical")) {
    g.physical.assign(nc, 1);
    g.names.push_back(std::string("3 1 \"") + kAllElementsSet + "\"");
  }
  for (long p : g.physical) g.entity_of.emplace(p, 0);
  int next_entity = 1;
  for (auto& [p, entity] : g.entity_of) {
    entity = next_entity++;
    g.boxes[entity] = {Eigen::RowVector3d::Constant(INFINITY), Eigen::RowVector3d::Constant(-INFINITY)};
  }
  for (int c = 0; c < nc; ++c) {
    auto& [lo, hi] = g.boxes[g.entity_of[g.physical[c]]];
    for (int k = 0; k < node_count(mesh.types[c]); ++k) {
      lo = lo.cwiseMin(mesh.V.row(mesh.C(c, k)));
      hi = hi.cwiseMax(mesh.V.row(mesh.C(c, k)));
    }
  }
  // Element blocks are runs of consecutive cells of one entity and type, so cell order survives a round trip.
  for (int c = 0; c < nc; ++c) {
    if (g.runs.empty() || mesh.types[c] != mesh.types[c - 1] || g.physical[c] != g.physical[c - 1])
      g.runs.push_back({c, c});
    g.runs.back().second = c + 1;
  }
  // Boundary faces, outward, triangles (Gmsh type 2) and quads (3) apart.
  for (int s : g.surfaces)
    for (int size : {3, 4}) {
      GmshLayout::FaceBlock block{s, size == 3 ? 2 : 3, {}};
      for (const CellFace& cf : sides.faces[s])
        if (cell_faces(mesh.types[cf.cell])[cf.face].size == size)
          block.faces.push_back(face_vertices(mesh, cf.cell, cf.face));
      g.num_faces += block.faces.size();
      if (!block.faces.empty()) g.face_blocks.push_back(std::move(block));
    }
  return g;
}

void write_box(std::ostream& out, const Eigen::RowVector3d& lo, const Eigen::RowVector3d& hi) {
  for (int k = 0; k < 3; ++k) out << ' ' << format_double(lo[k]);
  for (int k = 0; k < 3; ++k) out << ' ' << format_double(hi[k]);
}

void write_entities(std::ostream& out, const VolumeMesh& mesh, const SideSets& sides, const GmshLayout& g) {
  if (!g.names.empty()) {
    out << "$PhysicalNames\n" << g.names.size() << '\n';
    for (const std::string& name : g.names) out << name << '\n';
    out << "$EndPhysicalNames\n";
  }
  out << "$Entities\n0 0 " << g.surfaces.size() << ' ' << g.entity_of.size() << "\n";
  for (int s : g.surfaces) {  // surface entity s+1 with physical tag s+1, no bounding curves
    Eigen::RowVector3d lo = Eigen::RowVector3d::Constant(INFINITY), hi = -lo;
    for (const CellFace& cf : sides.faces[s])
      for (int v : face_vertices(mesh, cf.cell, cf.face)) {
        lo = lo.cwiseMin(mesh.V.row(v));
        hi = hi.cwiseMax(mesh.V.row(v));
      }
    out << s + 1;
    write_box(out, lo, hi);
    out << " 1 " << s + 1 << " 0\n";
  }
  for (const auto& [p, entity] : g.entity_of) {
    out << entity;
    write_box(out, g.boxes.at(entity).first, g.boxes.at(entity).second);
    out << (p > 0 ? " 1 " + std::to_string(p) : std::string(" 0")) << " 0\n";
  }
  out << "$EndEntities\n";
}

void write_elements(std::ostream& out, const VolumeMesh& mesh, const GmshLayout& g) {
  const size_t num_elements = mesh.num_cells() + g.num_faces;
  out << "$Elements\n" << g.runs.size() + g.face_blocks.size() << ' ' << num_elements << " 1 " << num_elements << "\n";
  for (const auto& [first, end] : g.runs) {
    const CellType type = mesh.types[first];
    out << "3 " << g.entity_of.at(g.physical[first]) << ' ' << gmsh_type_code(type) << ' ' << end - first << '\n';
    for (int c = first; c < end; ++c) {
      out << c + 1;
      for (int k = 0; k < node_count(type); ++k)
        out << ' ' << mesh.C(c, type == CellType::Wedge ? kPrismToWedge[k] : k) + 1;
      out << '\n';
    }
  }
  size_t tag = mesh.num_cells();
  for (const GmshLayout::FaceBlock& block : g.face_blocks) {
    out << "2 " << block.side + 1 << ' ' << block.gmsh_type << ' ' << block.faces.size() << '\n';
    for (const std::vector<int>& face : block.faces) {
      out << ++tag;
      for (int v : face) out << ' ' << v + 1;
      out << '\n';
    }
  }
  out << "$EndElements\n";
}

}  // namespace

void write_gmsh(const std::string& file, const VolumeMesh& mesh) {
  const int nv = mesh.num_vertices();
  const SideSets sides = side_sets(mesh);
  const GmshLayout layout = gmsh_layout(file, mesh, sides);
  std::ofstream out(file);
  if (!out) throw Error(file, "cannot open for writing");
  out << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  write_entities(out, mesh, sides, layout);
  // All nodes in one block, classified on the first volume entity.
  out << "$Nodes\n1 " << nv << " 1 " << nv << "\n3 " << layout.entity_of.begin()->second << " 0 " << nv << "\n";
  for (int i = 0; i < nv; ++i) out << i + 1 << '\n';
  for (int i = 0; i < nv; ++i)
    out << format_double(mesh.V(i, 0)) << ' ' << format_double(mesh.V(i, 1)) << ' ' << format_double(mesh.V(i, 2))
        << '\n';
  out << "$EndNodes\n";
  write_elements(out, mesh, layout);
  out.flush();
  if (!out) throw Error(file, "write failed (disk full?)");
}

}  // namespace facehex::io
