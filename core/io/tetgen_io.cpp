#include "core/io/tetgen_io.h"

#include <vector>

#include "core/io/io_util.h"

namespace facehex::io {

namespace {

// A header count that must be within [lo, hi].
long header_count(const LineParser& in, size_t i, const std::string& what, long lo, long hi) {
  const long n = in.integer(i, what);
  if (n < lo || n > hi) {
    in.fail(what + " is " + std::to_string(n) + ", expected " +
            (hi == lo ? std::to_string(lo) : std::to_string(lo) + ".." + std::to_string(hi)));
  }
  return n;
}

// After the announced records only comments may follow: more data means the header count is wrong.
void expect_end(LineParser& in, long count, const std::string& what) {
  if (in.next()) in.fail("more " + what + " than the " + std::to_string(count) + " announced in the header");
}

}  // namespace

VolumeMesh read_tetgen(const std::string& node_path, const std::string& ele_path) {
  VolumeMesh mesh;
  long base = 0;
  {
    LineParser in(node_path, '#');
    in.require_next("the header '<#points> 3 <#attributes> <#markers>'");
    const long n = header_count(in, 0, "number of points", 1, 1L << 30);
    header_count(in, 1, "dimension", 3, 3);
    const long n_attr = in.size() > 2 ? header_count(in, 2, "number of attributes", 0, 1000) : 0;
    const long n_mark = in.size() > 3 ? header_count(in, 3, "number of boundary markers", 0, 1) : 0;
    std::vector<double> coords, attributes, markers;
    for (long i = 0; i < n; ++i) {
      in.require_next("point " + std::to_string(i + 1) + " of " + std::to_string(n));
      in.require_fields(4 + n_attr + n_mark, "a point (id, x, y, z, attributes, marker)");
      const long id = in.integer(0, "point id");
      if (i == 0) {
        if (id != 0 && id != 1) in.fail("first point id is " + std::to_string(id) + ", expected 0 or 1");
        base = id;
      } else if (id != base + i) {
        in.fail("point id " + std::to_string(id) + " out of sequence, expected " + std::to_string(base + i));
      }
      for (int k = 0; k < 3; ++k) coords.push_back(in.real(1 + k, "a coordinate"));
      for (long k = 0; k < n_attr; ++k) attributes.push_back(in.real(4 + k, "a point attribute"));
      if (n_mark) markers.push_back(static_cast<double>(in.integer(4 + n_attr, "boundary marker")));
    }
    expect_end(in, n, "points");
    mesh.V = rows_to_matrix(coords, 3);
    if (n_attr) mesh.point_data["tetgen_attributes"] = rows_to_matrix(attributes, static_cast<int>(n_attr));
    if (n_mark) mesh.point_data["tetgen_boundary_marker"] = rows_to_matrix(markers, 1);
  }
  {
    LineParser in(ele_path, '#');
    in.require_next("the header '<#tets> <4|10> <#attributes>'");
    const long n = header_count(in, 0, "number of tetrahedra", 1, 1L << 30);
    const long per_tet = header_count(in, 1, "nodes per tetrahedron", 4, 10);
    if (per_tet != 4 && per_tet != 10) in.fail("nodes per tetrahedron must be 4 or 10");
    const long n_attr = in.size() > 2 ? header_count(in, 2, "number of attributes", 0, 1000) : 0;
    std::vector<double> attributes;
    CellBuilder cells;
    for (long i = 0; i < n; ++i) {
      in.require_next("tetrahedron " + std::to_string(i + 1) + " of " + std::to_string(n));
      in.require_fields(1 + per_tet + n_attr, "a tetrahedron (id, nodes, attributes)");
      int nodes[4];
      for (int k = 0; k < 4; ++k) {
        const long id = in.integer(1 + k, "node id");
        if (id < base || id >= base + mesh.num_vertices()) {
          in.fail("node id " + std::to_string(id) + " out of range " + std::to_string(base) + ".." +
                  std::to_string(base + mesh.num_vertices() - 1));
        }
        nodes[k] = static_cast<int>(id - base);
      }
      if (const int k = find_repeated(nodes, 4); k >= 0) {
        in.fail("tetrahedron " + std::string(in.field(0)) + " uses node " + std::to_string(nodes[k] + base) + " twice");
      }
      if (const int k = find_repeated(nodes, 4); k >= 0) {
        in.fail("tetrahedron " + std::string(in.field(0)) + " uses node " + std::to_string(nodes[k] + base) + " twice");
      }
      for (long k = 0; k < n_attr; ++k) attributes.push_back(in.real(1 + per_tet + k, "a tetrahedron attribute"));
      cells.add(CellType::Tet, nodes);
    }
    expect_end(in, n, "tetrahedra");
    cells.finish(&mesh);
    if (n_attr) mesh.cell_data["tetgen_attributes"] = rows_to_matrix(attributes, static_cast<int>(n_attr));
  }
  check_volume_mesh(ele_path, mesh);
  return mesh;
}

}  // namespace facehex::io
