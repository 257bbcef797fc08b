#pragma once
// ANSYS node/element text files (.node + .elem, as written by NWRITE / EWRITE) -> hex-dominant VolumeMesh.
//
// .node: one node per line, "id x y z". NWRITE writes fixed-width columns (8 characters for the id, 20 for each
//        coordinate) and a negative coordinate then glues to the field before it ("     124-0.534E-08  77.75 ...").
// .elem: one element per line, "I J K L M N O P <attributes...> <element number>" (EWRITE: MAT TYPE REAL SECNUM
//        ESYS IEL). An 8-node brick is a VTK hexahedron in the same node order. A prism is written as a brick
//        collapsed with K = L and O = P; it becomes the VTK wedge (I, K, J, M, O, N), reversed because VTK's wedge
//        base normal points away from the top triangle while ANSYS's points towards it. Other collapsed patterns
//        (tets, pyramids) are rejected.
// Node ids may have gaps; they are kept in point_data "ansys_node_id", the element numbers in cell_data
// "ansys_element_id".
#include <Eigen/Core>
#include <string>
#include <string_view>

#include "core/mesh/mesh.h"

namespace facehex {

VolumeMesh read_ansys_mesh(const std::string& node_path, const std::string& elem_path);

// Parses one .node line: whitespace-separated when that gives exactly 4 fields, else the fixed-width columns
// 8/20/20/20. False when neither gives an integer id and three finite coordinates.
bool parse_ansys_node_line(std::string_view line, long* id, Eigen::Vector3d* xyz);

}  // namespace facehex
