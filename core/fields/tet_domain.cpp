#include "core/fields/tet_domain.h"

#include "core/fields/constraint_set.h"
#include "core/mesh/hex_to_tets.h"
#include "core/mesh/side_mask.h"

namespace facehex {

TetDomain auxiliary_domain(const VolumeMesh& hex) {
  const AuxiliaryTets aux = split_into_tets(hex);
  TetDomain d;
  d.V = hex.V;
  d.T = aux.T;
  d.side_mask = side_mask_of(hex);
  if (d.side_mask.size() == d.V.rows()) d.relaxed_corner_vertices = relax_corner_quads(hex, d.side_mask);
  d.hex_vertices = hex.num_vertices();
  d.non_positive_tets = aux.non_positive_tets;
  d.description = "auxiliary tets (hexes and wedges split, paper 3.2)";
  return d;
}

TetDomain own_domain(const VolumeMesh& tets) {
  TetDomain d;
  d.V = tets.V;
  d.T = tets.tets();
  d.side_mask = side_mask_of(tets);
  d.hex_vertices = tets.num_vertices();
  d.description = "the model's own tets";
  return d;
}

}  // namespace facehex
