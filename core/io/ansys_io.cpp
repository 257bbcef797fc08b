#include "core/io/ansys_io.h"

#include <cmath>
#include <unordered_map>
#include <vector>

#include "core/io/io_util.h"

namespace facehex {

namespace {

constexpr size_t kIdWidth = 8;  // NWRITE column widths
constexpr size_t kCoordWidth = 20;

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

bool parse_coordinate(std::string_view s, double* x) { return io::parse_real(trim(s), x) && std::isfinite(*x); }

}  // namespace

bool parse_ansys_node_line(std::string_view line, long* id, Eigen::Vector3d* xyz) {
  const std::vector<std::string_view> fields = io::split_fields(line);
  if (fields.size() == 4) {
    return io::parse_integer(fields[0], id) && parse_coordinate(fields[1], &(*xyz)[0]) &&
           parse_coordinate(fields[2], &(*xyz)[1]) && parse_coordinate(fields[3], &(*xyz)[2]);
  }
  // Fixed width; the last field may be shorter when trailing blanks were stripped.
  if (line.size() <= kIdWidth + 2 * kCoordWidth) return false;
  if (!io::parse_integer(trim(line.substr(0, kIdWidth)), id)) return false;
  for (int k = 0; k < 3; ++k) {
    const std::string_view field =
        line.substr(kIdWidth + k * kCoordWidth, k < 2 ? kCoordWidth : std::string_view::npos);
    if (!parse_coordinate(field, &(*xyz)[k])) return false;
  }
  return true;
}

VolumeMesh read_ansys_mesh(const std::string& node_path, const std::string& elem_path) {
  VolumeMesh mesh;
  std::vector<double> coords, node_ids;
  std::unordered_map<long, int> node_index;
  {
    io::LineParser in(node_path);
    while (in.next()) {
      long id = 0;
      Eigen::Vector3d p;
      if (!parse_ansys_node_line(in.line(), &id, &p)) {
        in.fail("cannot read node line: expected 'id x y z' (separated by blanks or in columns of 8/20/20/20)");
      }
      if (!node_index.emplace(id, static_cast<int>(node_ids.size())).second) {
        in.fail("node id " + std::to_string(id) + " defined twice");
      }
      node_ids.push_back(static_cast<double>(id));
      coords.insert(coords.end(), {p[0], p[1], p[2]});
    }
  }
  mesh.V = io::rows_to_matrix(coords, 3);
  mesh.point_data["ansys_node_id"] = io::rows_to_matrix(node_ids, 1);

  io::CellBuilder cells;
  std::vector<double> element_ids;
  std::unordered_map<long, int> element_line;  // element number -> line, to report duplicates
  {
    io::LineParser in(elem_path);
    size_t columns = 0;
    while (in.next()) {
      // All lines of one file have the same columns: a shorter line is a cut or damaged one.
      if (columns == 0) {
        in.require_fields(9, "an element (8 node ids, attributes, element number)");
        columns = in.size();
      } else if (in.size() != columns) {
        in.fail("element line has " + std::to_string(in.size()) + " columns, the first one has " +
                std::to_string(columns));
      }
      const long number = in.integer(columns - 1, "element number");
      for (size_t k = 8; k + 1 < columns; ++k) in.integer(k, "element attribute");
      if (const auto [it, fresh] = element_line.emplace(number, in.line_number()); !fresh) {
        in.fail("element number " + std::to_string(number) + " used twice (first on line " +
                std::to_string(it->second) + ")");
      }
      long id[8];
      int n[8];
      for (int k = 0; k < 8; ++k) {
        id[k] = in.integer(k, "node id");
        const auto it = node_index.find(id[k]);
        if (it == node_index.end()) {
          in.fail("element " + std::to_string(number) + " refers to node " + std::to_string(id[k]) +
                  ", which is not in " + node_path);
        }
        n[k] = it->second;
      }
      bool distinct8 = true, distinct6 = true;  // all of I..P / all of I J K M N O differ
      for (int a = 0; a < 8; ++a)
        for (int b = a + 1; b < 8; ++b) {
          if (n[a] != n[b]) continue;
          distinct8 = false;
          if (a != 3 && a != 7 && b != 3 && b != 7) distinct6 = false;
        }
      if (distinct8) {
        cells.add(CellType::Hex, n);
      } else if (n[2] == n[3] && n[6] == n[7] && distinct6) {
        const int wedge[6] = {n[0], n[2], n[1], n[4], n[6], n[5]};
        cells.add(CellType::Wedge, wedge);
      } else {
        std::string nodes;
        for (long i : id) nodes += " " + std::to_string(i);
        in.fail("element " + std::to_string(number) + " has nodes" + nodes +
                ": repeated nodes other than a prism's K=L, O=P are not supported");
      }
      element_ids.push_back(static_cast<double>(number));
    }
  }
  cells.finish(&mesh);
  mesh.cell_data["ansys_element_id"] = io::rows_to_matrix(element_ids, 1);
  io::check_volume_mesh(elem_path, mesh);
  return mesh;
}

}  // namespace facehex
