#pragma once
// FEBio input files (.feb, febio_spec version 4.0) <-> VolumeMesh. Internal to core/io: use mesh_io.h.
//
// The writer produces a complete, runnable 4.0 model whose mesh part is exact and whose physics are placeholders to
// replace (docs/export.md). Units mm, N, MPa (density in tonne/mm^3).
//   Module solid; Control: STATIC, 10 steps of 0.1
//   Material soft_tissue: neo-Hookean, E = 0.015 MPa, v = 0.45 (placeholder)
//   Mesh: Nodes (node i+1 = vertex i); Elements type hex8 / penta6 / tet4 named HEX / WEDGE / TET (element c+1 =
//         cell c; FEBio's penta6, like Abaqus' C3D6, has its first triangle's normal pointing towards the second, so
//         wedges are reordered, see fe_sets.h); NodeSet and Surface (quad4 / tri3 facets, outward) per side;
//         ElementSet ALL. FEBio makes an element set of each Elements part, so HEX / WEDGE / TET exist as sets too.
//   MeshDomains: a SolidDomain per part, material soft_tissue
//   MeshData: per part an ElementData type="mat_axis" (FEBio 4.0 requires its elem_set to be a single domain) with
//             per element a = e1 and d = e2 of its material frame, so FEBio's local axes are e1, e2, e3
//   Boundary: zero displacement of the BONE node set (when the mesh has sides); no loads
//   Output: plot file with displacement and stress
//
// The reader takes Mesh/Nodes, Mesh/Elements (hex8, penta6, tet4), Mesh/NodeSet and MeshData/ElementData of type
// mat_axis, skipping the rest; cells are ordered by element id, node sets named after the sides become "side_mask"
// and mat_axis becomes "frame_e1".."frame_e3" (elements without one get the global axes, as in FEBio).
#include <string>

#include "core/mesh/mesh.h"

namespace facehex::io {

VolumeMesh read_febio(const std::string& path);
void write_febio(const std::string& file, const VolumeMesh& mesh);

}  // namespace facehex::io
