#pragma once
// TetGen .node/.ele files (https://wias-berlin.de/software/tetgen/fformats.html) -> tet VolumeMesh. Internal to
// core/io: use mesh_io.h.
//
// .node: "<#points> <dim=3> <#attributes> <boundary markers 0|1>", then "<id> <x> <y> <z> [attributes] [marker]".
// .ele : "<#tets> <nodes per tet 4|10> <#attributes>", then "<id> <n1> ... <n4|n10> [attributes]".
// '#' starts a comment. Numbering starts at 0 or 1, as the first point of the .node says. Second-order (10-node)
// tets keep their 4 corners. Attributes go to point_data "tetgen_attributes" / cell_data "tetgen_attributes",
// boundary markers to point_data "tetgen_boundary_marker".
#include <string>

#include "core/mesh/mesh.h"

namespace facehex::io {

VolumeMesh read_tetgen(const std::string& node_path, const std::string& ele_path);

}  // namespace facehex::io
