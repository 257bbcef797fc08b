#pragma once
// Neighbourhoods of vertex sets in cell rings.
#include <vector>

#include "core/mesh/mesh.h"

namespace facehex {

// The vertices `marked` (#V flags) and those sharing a cell with them, grown `rings` times: the neighbourhood of a
// set of vertices in cell rings.
std::vector<char> within_cell_rings(const VolumeMesh& mesh, std::vector<char> marked, int rings);

}  // namespace facehex
