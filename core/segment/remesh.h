#pragma once
// Isotropic remeshing of a closed, labelled triangle surface (Botsch & Kobbelt 2004, "A remeshing approach to
// multiresolution modeling"): repeated rounds of splitting long edges, collapsing short ones, flipping edges towards
// valence 6 and tangential smoothing, with the vertices projected back onto the input surface; then Delaunay flips. The
// result has near-equilateral triangles of about the target edge length, which TetGen needs to mesh the volume without
// refining the boundary many times over (marching-cubes triangles are slivers).
//
// Face labels are kept: an edge between faces of different labels is a feature edge. Feature edges are only split
// and collapsed along themselves, never flipped; their vertices slide along the feature line and are projected onto
// the input's feature lines between the same two labels; vertices where three labels meet (or a feature line ends or
// branches) do not move. So every labelled patch keeps its boundary and its connectivity, and the surface keeps its
// topology (collapses respect the link condition).
#include "core/mesh/mesh.h"

namespace facehex {

// `surface` must be closed and manifold, with one label per face (any non-negative integers).
SurfaceMesh remesh_isotropic(const SurfaceMesh& surface, double target_edge_length, int rounds = 8);

}  // namespace facehex
