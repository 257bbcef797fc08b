#include "core/io/fe_sets.h"

#include <algorithm>
#include <array>
#include <set>

#include "core/fields/constraint_set.h"
#include "core/mesh/cell_faces.h"
#include "core/mesh/corner_jacobian.h"
#include "core/util/error.h"

namespace facehex {

namespace {

constexpr std::array<CellType, 3> kExportOrder = {CellType::Hex, CellType::Wedge, CellType::Tet};

// "3 of 120 elements are inverted (elements 5, 17, 33)": the first ids only, a mesh can have thousands.
std::string describe_cells(const std::vector<int>& cells, int total, const std::string& what) {
  constexpr size_t kShown = 10;
  std::string ids;
  for (size_t i = 0; i < std::min(cells.size(), kShown); ++i) ids += (i ? ", " : "") + std::to_string(cells[i] + 1);
  if (cells.size() > kShown) ids += ", ...";
  return std::to_string(cells.size()) + " of " + std::to_string(total) + " elements " + what + " (element ids " + ids +
         ")";
}

// Cells whose nodes, in any order, are those of an earlier cell; ascending.
std::vector<int> repeated_cells(const VolumeMesh& mesh) {
  std::set<std::array<int, 8>> seen;
  std::vector<int> repeated;
  for (int c = 0; c < mesh.num_cells(); ++c) {
    std::array<int, 8> nodes;
    for (int k = 0; k < 8; ++k) nodes[k] = mesh.C(c, k);
    std::sort(nodes.begin(), nodes.end());
    if (!seen.insert(nodes).second) repeated.push_back(c);
  }
  return repeated;
}

}  // namespace

const char* element_set_name(CellType type) {
  switch (type) {
    case CellType::Hex:
      return "HEX";
    case CellType::Wedge:
      return "WEDGE";
    case CellType::Tet:
      return "TET";
  }
  return "";
}

int solver_node(CellType type, int k) {
  static constexpr int kWedge[6] = {0, 2, 1, 3, 5, 4};
  return type == CellType::Wedge ? kWedge[k] : k;
}

SideSets side_sets(const VolumeMesh& mesh) {
  SideSets sets;
  const Eigen::VectorXi mask = side_mask_of(mesh);
  if (mask.size() == 0) return sets;
  sets.present = true;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    for (int s = 0; s < kNumSides; ++s)
      if (mask(v) & side_bit(static_cast<Side>(s))) sets.nodes[s].push_back(v);
  const FaceNeighbors neighbors = face_neighbors(mesh);
  for (int c = 0; c < mesh.num_cells(); ++c)
    for (int f = 0; f < static_cast<int>(neighbors[c].size()); ++f) {
      if (neighbors[c][f][0] >= 0) continue;
      int common = ~0;
      for (int v : face_vertices(mesh, c, f)) common &= mask(v);
      for (int s = 0; s < kNumSides; ++s)
        if (common & side_bit(static_cast<Side>(s))) sets.faces[s].push_back({c, f});
    }
  return sets;
}

std::vector<CellType> cell_types_present(const VolumeMesh& mesh) {
  std::vector<CellType> types;
  for (CellType t : kExportOrder)
    if (mesh.count(t) > 0) types.push_back(t);
  return types;
}

std::vector<int> cells_of_type(const VolumeMesh& mesh, CellType type) {
  std::vector<int> cells;
  for (int c = 0; c < mesh.num_cells(); ++c)
    if (mesh.types[c] == type) cells.push_back(c);
  return cells;
}

std::optional<MaterialFrames> export_frames(const VolumeMesh& mesh) {
  const auto has = [&](const char* name) {
    const auto it = mesh.cell_data.find(name);
    return it != mesh.cell_data.end() && it->second.cols() == 3;
  };
  if (has(kFrameArrays[0]) && has(kFrameArrays[1]) && has(kFrameArrays[2])) {
    return MaterialFrames{
        mesh.cell_data.at(kFrameArrays[0]), mesh.cell_data.at(kFrameArrays[1]), mesh.cell_data.at(kFrameArrays[2]), {}};
  }
  const auto uvw = mesh.point_data.find("uvw");
  if (uvw == mesh.point_data.end() || uvw->second.cols() != 3) return std::nullopt;
  return material_frames(mesh, uvw->second);
}

std::optional<Eigen::MatrixXd> side_mask_from_node_sets(int num_vertices,
                                                        const std::map<std::string, std::vector<int>>& node_sets) {
  Eigen::MatrixXd mask = Eigen::MatrixXd::Zero(num_vertices, 1);
  bool any = false;
  for (int s = 0; s < kNumSides; ++s) {
    const auto it = node_sets.find(kSideSetNames[s]);
    if (it == node_sets.end()) continue;
    any = true;
    for (int v : it->second) mask(v) = static_cast<double>(static_cast<int>(mask(v)) | side_bit(static_cast<Side>(s)));
  }
  if (!any) return std::nullopt;
  return mask;
}

void attach_frames(VolumeMesh& mesh, const MaterialFrames& frames) {
  mesh.cell_data[kFrameArrays[0]] = frames.e1;
  mesh.cell_data[kFrameArrays[1]] = frames.e2;
  mesh.cell_data[kFrameArrays[2]] = frames.e3;
}

void check_fe_exportable(const std::string& path, const VolumeMesh& mesh, bool allow_inverted) {
  if (const std::vector<int> repeated = repeated_cells(mesh); !repeated.empty()) {
    throw Error(path, "refusing to export: " +
                          describe_cells(repeated, mesh.num_cells(), "repeat the nodes of an earlier element") +
                          ", which would double the stiffness there; remove the duplicates");
  }
  if (allow_inverted) return;
  const std::string force = "; fix the mesh, or force the export (--force-export)";
  const CornerJacobianCheck check = check_corner_jacobians(mesh);
  if (!check.inverted.empty()) {
    throw Error(path, "refusing to export: " + describe_cells(check.inverted, mesh.num_cells(), "are inverted") +
                          ", the solver would reject them" + force);
  }
  if (const auto frames = export_frames(mesh); frames && !frames->degenerate.empty()) {
    throw Error(path, "refusing to export: " +
                          describe_cells(frames->degenerate, mesh.num_cells(),
                                         "have parametric coordinates \"uvw\" that give no material frame") +
                          force);
  }
}

void attach_fe_arrays(VolumeMesh& mesh) {
  const SideSets sets = side_sets(mesh);
  if (sets.present) {
    for (int s = 0; s < kNumSides; ++s) {
      Eigen::MatrixXd in_set = Eigen::MatrixXd::Zero(mesh.num_vertices(), 1);
      for (int v : sets.nodes[s]) in_set(v) = 1;
      mesh.point_data[std::string("nset_") + kSideSetNames[s]] = in_set;
      Eigen::MatrixXd face_bits = Eigen::MatrixXd::Zero(mesh.num_cells(), 1);
      for (const CellFace& cf : sets.faces[s]) face_bits(cf.cell) += 1 << cf.face;
      mesh.cell_data[std::string("surf_") + kSideSetNames[s]] = face_bits;
    }
  }
  if (const auto frames = export_frames(mesh)) attach_frames(mesh, *frames);
}

}  // namespace facehex
