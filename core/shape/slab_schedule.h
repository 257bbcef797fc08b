#pragma once
// Which free vertices step at the same time in the shape solver's parallel sweeps.
//
// Vertices that share no cell can step at the same time: a step reads and writes only the cells around its vertex.
// The free vertices are cut, by their rank along the region's longest extent, into slabs whose cells reach at most
// into the neighbouring slab; the even slabs then step in parallel, then the odd ones. That is two waits per sweep
// whatever the thread count, so a thread that loses its core to another job delays a sweep once, rather than at each
// of the dozens of colour classes a graph colouring needs. The slabs depend on the mesh only: the result does not
// depend on the thread count. Fewer, thicker slabs where thin ones would share cells; one slab for a small region.
#include <vector>

#include "core/mesh/mesh.h"

namespace facehex {

// cells_of: #V lists of the cells around each vertex. Returns the slabs in order along the cut axis, each listing its
// vertices in ascending order.
std::vector<std::vector<int>> slab_schedule(const VolumeMesh& mesh, const std::vector<std::vector<int>>& cells_of,
                                            const std::vector<int>& free_vertices);

}  // namespace facehex
