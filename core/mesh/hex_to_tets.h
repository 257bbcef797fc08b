#pragma once
// The auxiliary tet mesh of a hex-dominant mesh (paper 3.2): every hex and wedge is split into tets without adding
// vertices, so each hex vertex carries its harmonic field values directly.
//
// Conformity: every quad face is cut along the diagonal through its smallest vertex id, and each cell is split as
// the cone from its smallest vertex id to the faces not containing it (each triangulated by that rule). Two cells
// sharing a quad therefore cut it the same way, and the faces through the cone apex are cut through the apex,
// which is their smallest vertex too. A hex gives 6 tets, a wedge 3, a tet itself.
#include <Eigen/Core>

#include "core/mesh/mesh.h"

namespace facehex {

struct AuxiliaryTets {
  Eigen::MatrixXi T;          // #T x 4, positively oriented where the cell's geometry allows
  Eigen::VectorXi parent;     // #T, the cell each tet comes from
  int non_positive_tets = 0;  // tets with volume <= 0 in the input geometry (a sign of badly shaped cells)
};

AuxiliaryTets split_into_tets(const VolumeMesh& mesh);

}  // namespace facehex
