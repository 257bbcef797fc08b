#pragma once
// Gmsh .msh (https://gmsh.info/doc/texinfo/gmsh.html#MSH-file-format) <-> VolumeMesh. Internal to core/io: use
// mesh_io.h.
//
// Reads ASCII 2.2 (2.x) and 4.1: nodes, and tets (type 4), hexes (5), prisms (6). Lower-dimensional elements
// (points, lines, triangles, quads: boundary and physical-group annotations) are skipped; any other volume element
// (pyramids, second-order cells) is an error. Gmsh prisms are reordered to VTK wedges (see gmsh_io.cpp). The
// physical tag of each volume element goes to cell_data "gmsh_physical" when the file has any.
// Writes ASCII 4.1, one volume entity per distinct value of cell_data "gmsh_physical" (if present). A mesh with point
// data "side_mask" also gets its side surfaces (fe_sets.h) as triangles and quads in physical surfaces 1..6 (side s
// -> s+1) named like the FE exports' surfaces ("SKIN_SURF", ...), and then, unless "gmsh_physical" is given, all
// cells in physical volume 1 "ALL" (Gmsh drops elements outside physical groups when it saves).
#include <string>

#include "core/mesh/mesh.h"

namespace facehex::io {

VolumeMesh read_gmsh(const std::string& path);
void write_gmsh(const std::string& file, const VolumeMesh& mesh);

}  // namespace facehex::io
