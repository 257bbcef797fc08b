#pragma once
// The tet domain on which a model is parameterized. Its first #Vm vertices are the model's own vertices, in order, so
// every vertex of a standard hex mesh carries its field values directly (paper 3.2); further vertices (if any) are
// added by domain builders such as closed_domain() (core/standard/closed_domain.h). A tet model is its own domain.
#include <Eigen/Core>
#include <string>

#include "core/mesh/mesh.h"

namespace facehex {

struct TetDomain {
  Eigen::MatrixXd V;                // #V x 3, rows 0..hex_vertices-1 are the hex vertices
  Eigen::MatrixXi T;                // #T x 4
  Eigen::VectorXi side_mask;        // #V (sides.h bits), or empty
  int hex_vertices = 0;             // #Vm: the model's own vertices (a standard's hex vertices)
  int non_positive_tets = 0;        // tets with volume <= 0 (badly shaped hex cells split into tets)
  std::string description;          // how it was built, for reports
  int relaxed_corner_vertices = 0;  // side labels dropped at shell corners (side_mask.h relax_corner_quads)
  int closed_openings = 0;          // openings closed by plugs (core/standard/closed_domain.h)
};

// The paper's auxiliary tet mesh: hexes and wedges split into tets, no vertex added (hex_to_tets.h).
TetDomain auxiliary_domain(const VolumeMesh& hex);

// A tet model as its own domain: its vertices, tets and side labels, nothing added.
TetDomain own_domain(const VolumeMesh& tets);

}  // namespace facehex
