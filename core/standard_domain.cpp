#include "core/standard_domain.h"

#include "core/constraint_set.h"
#include "core/hex_to_tets.h"
#include "core/side_mask.h"

namespace facehex {

StandardDomain auxiliary_domain(const VolumeMesh& hex) {
  const AuxiliaryTets aux = split_into_tets(hex);
  StandardDomain d;
  d.V = hex.V;
  d.T = aux.T;
  d.side_mask = side_mask_of(hex);
  if (d.side_mask.size() == d.V.rows()) d.relaxed_corner_vertices = relax_corner_quads(hex, d.side_mask);
  d.hex_vertices = hex.num_vertices();
  d.non_positive_tets = aux.non_positive_tets;
  d.description = "auxiliary tets (hexes and wedges split, paper 3.2)";
  return d;
}

}  // namespace facehex
