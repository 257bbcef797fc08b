#pragma once
// Checks a tet model before it is parameterized. Problems a user must fix are facehex::Error naming `source`:
// no tets, a node id out of range, degenerate (zero-volume) tets, tets of both orientations (some inverted),
// a face shared by three or more tets (non-manifold), several connected components.
// A model whose tets are ALL negatively oriented (another file convention) is repaired by swapping two nodes of
// every tet; the return value says so.
#include <string>

#include "core/mesh/mesh.h"

namespace facehex {

struct TetMeshCheck {
  bool reoriented = false;  // all tets were negative and have been flipped
  int boundary_faces = 0;
  double volume = 0;  // mm^3
};

TetMeshCheck check_and_orient_tet_mesh(VolumeMesh& mesh, const std::string& source);

}  // namespace facehex
