#include "core/mesh/cell_rings.h"

namespace facehex {

std::vector<char> within_cell_rings(const VolumeMesh& mesh, std::vector<char> marked, int rings) {
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<char> grown = marked;
    for (int c = 0; c < mesh.num_cells(); ++c) {
      bool touches = false;
      for (int i = 0; i < node_count(mesh.types[c]); ++i) touches |= marked[mesh.C(c, i)] != 0;
      if (touches)
        for (int i = 0; i < node_count(mesh.types[c]); ++i) grown[mesh.C(c, i)] = 1;
    }
    marked.swap(grown);
  }
  return marked;
}

}  // namespace facehex
