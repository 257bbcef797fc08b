#pragma once
// The closed triangle surface bounding {phi < 0} of a field on a voxel grid (Flying Edges, so linear
// interpolation along voxel edges: no voxel staircase when phi is smooth). Its triangles are as fine as the grid and
// often slivers: remesh.h makes a mesh of it.
#include "core/mesh/mesh.h"
#include "core/segment/voxel_grid.h"
#include "core/util/error.h"

namespace facehex {

// The zero level touches itself (an edge of four triangles, a vertex joining two sheets): it bounds no solid that
// TetGen could fill.
class NonManifoldSurface : public Error {
 public:
  NonManifoldSurface() : Error("segment", "the soft-tissue surface is not a closed manifold") {}
};

// Triangles are outward oriented (right-hand normal towards phi > 0). Only the largest connected piece is kept.
// Throws facehex::Error("segment", ...) if phi has no negative region, NonManifoldSurface if its surface is not a
// closed manifold.
SurfaceMesh zero_level_surface(const Field& phi);

// True if every edge has exactly two faces, used once in each direction.
bool is_closed_manifold(const SurfaceMesh& surface);

}  // namespace facehex
