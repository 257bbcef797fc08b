#include "core/mesh/cell_faces.h"

#include <algorithm>

namespace facehex {

const std::vector<LocalFace>& cell_faces(CellType type) {
  static const std::vector<LocalFace> tet = {
      {3, {1, 2, 3, -1}}, {3, {0, 3, 2, -1}}, {3, {0, 1, 3, -1}}, {3, {0, 2, 1, -1}}};
  static const std::vector<LocalFace> wedge = {
      {3, {0, 1, 2, -1}}, {3, {3, 5, 4, -1}}, {4, {0, 3, 4, 1}}, {4, {1, 4, 5, 2}}, {4, {2, 5, 3, 0}}};
  static const std::vector<LocalFace> hex = {{4, {0, 3, 2, 1}}, {4, {4, 5, 6, 7}}, {4, {0, 1, 5, 4}},
                                             {4, {1, 2, 6, 5}}, {4, {2, 3, 7, 6}}, {4, {3, 0, 4, 7}}};
  switch (type) {
    case CellType::Tet:
      return tet;
    case CellType::Wedge:
      return wedge;
    case CellType::Hex:
      return hex;
  }
  return hex;
}

int opposite_face(CellType type, int face) {
  if (type == CellType::Hex) {
    static constexpr int opposite[6] = {1, 0, 4, 5, 2, 3};
    return opposite[face];
  }
  if (type == CellType::Wedge && face < 2) return 1 - face;
  return -1;
}

std::vector<int> face_vertices(const VolumeMesh& mesh, int c, int f) {
  const LocalFace& lf = cell_faces(mesh.types[c])[f];
  std::vector<int> v(lf.size);
  for (int k = 0; k < lf.size; ++k) v[k] = mesh.C(c, lf.node[k]);
  return v;
}

FaceNeighbors face_neighbors(const VolumeMesh& mesh) {
  struct Record {
    std::array<int, 4> key;  // sorted vertex ids, padded with -1 at the front for triangles
    int cell, face;
  };
  std::vector<Record> records;
  FaceNeighbors out(mesh.num_cells());
  for (int c = 0; c < mesh.num_cells(); ++c) {
    const auto& faces = cell_faces(mesh.types[c]);
    out[c].assign(faces.size(), {-1, -1});
    for (int f = 0; f < static_cast<int>(faces.size()); ++f) {
      std::array<int, 4> key = {-1, -1, -1, -1};
      const auto v = face_vertices(mesh, c, f);
      std::copy(v.begin(), v.end(), key.begin() + (4 - v.size()));
      std::sort(key.begin(), key.end());
      records.push_back({key, c, f});
    }
  }
  std::sort(records.begin(), records.end(), [](const Record& a, const Record& b) { return a.key < b.key; });
  for (size_t i = 0; i + 1 < records.size(); ++i)
    if (records[i].key == records[i + 1].key) {
      out[records[i].cell][records[i].face] = {records[i + 1].cell, records[i + 1].face};
      out[records[i + 1].cell][records[i + 1].face] = {records[i].cell, records[i].face};
      ++i;
    }
  return out;
}

}  // namespace facehex
