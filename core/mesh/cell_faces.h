#pragma once
// Faces of VTK cells (node order of mesh.h) and face adjacency of volume meshes.
// Faces are listed with right-hand normals pointing OUT of a positively oriented cell.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "core/mesh/mesh.h"

namespace facehex {

struct LocalFace {
  int size;                 // 3 or 4
  std::array<int, 4> node;  // local node indices, node[3] = -1 for triangles
};

// The faces of a cell type: tet 4, wedge 5 (two triangles first), hex 6.
const std::vector<LocalFace>& cell_faces(CellType type);

// The face opposite `face` in the cell (hex: the parallel quad; wedge: the other triangle), or -1 if none.
int opposite_face(CellType type, int face);

// Face adjacency of a volume mesh: neighbor[c][f] = {cell, face} across face f of cell c, or {-1, -1} on the boundary.
using FaceNeighbors = std::vector<std::vector<std::array<int, 2>>>;
FaceNeighbors face_neighbors(const VolumeMesh& mesh);

// Global vertex ids of face f of cell c, in the outward order (size 3 or 4).
std::vector<int> face_vertices(const VolumeMesh& mesh, int c, int f);

}  // namespace facehex
