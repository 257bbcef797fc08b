#include "core/mesh/mesh.h"

#include <algorithm>
#include <cassert>

namespace facehex {

const char* cell_type_name(CellType t) {
  switch (t) {
    case CellType::Tet:
      return "tet";
    case CellType::Wedge:
      return "wedge";
    case CellType::Hex:
      return "hex";
  }
  return "unknown";
}

int VolumeMesh::count(CellType t) const { return static_cast<int>(std::count(types.begin(), types.end(), t)); }

Eigen::MatrixXi VolumeMesh::tets() const {
  assert(is_tet_mesh());
  return C.leftCols(4);
}

VolumeMesh VolumeMesh::from_tets(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  VolumeMesh m;
  m.V = V;
  m.C = Eigen::MatrixXi::Constant(T.rows(), 8, -1);
  m.C.leftCols(4) = T;
  m.types.assign(T.rows(), CellType::Tet);
  return m;
}

}  // namespace facehex
