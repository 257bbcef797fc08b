#pragma once
// Tet models of a hex standard's own volume, for self-maps whose answer is the identity: its cells split into tets
// (openings left open as they are in the mesh) and TetGen re-meshes of the open volume or of the closed one (openings
// filled, core/standard/closed_domain.h). Each carries point data "side_mask" as a segmented patient does.
#include <string>

#include "core/mesh/mesh.h"

namespace facehex {

// The standard's cells split into tets with its side labels: the auxiliary split (hex_to_tets.h, no vertex added),
// except where it gives a non-positive tet (the standard's most sheared cells): such a cell is split as a cone from
// an inner point over its quads cut through their centres, and its face neighbours as cones over their faces cut
// the same way, so the model conforms and is positively oriented. The standard's vertices come first.
VolumeMesh split_hex_model(const VolumeMesh& standard);

// The boundary of the standard's open (split hexes) or closed volume, re-meshed isotropically at `edge_length` mm
// (core/segment/remesh.h) and tetrahedralized by TetGen at that edge length; each boundary triangle keeps the side
// common to the vertices of the face it came from (the walls of open openings: none).
VolumeMesh tetgen_remesh(const VolumeMesh& standard, bool closed, double edge_length);

}  // namespace facehex
