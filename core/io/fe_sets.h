#pragma once
// What the finite-element exports (Abaqus/CalculiX .inp, FEBio .feb, Gmsh .msh, and the .vtu arrays) attach to a
// volume mesh, in one place so that every format uses the same names and ids (see docs/export.md):
//
//   side (sides.h)  node set        boundary-face surface
//   u0              LATERAL_NEG_X   LATERAL_NEG_X_SURF
//   u1              LATERAL_POS_X   LATERAL_POS_X_SURF
//   v0              BOTTOM          BOTTOM_SURF
//   v1              TOP             TOP_SURF
//   w0              BONE            BONE_SURF
//   w1              SKIN            SKIN_SURF
//
// A node is in a side's set when its point-data "side_mask" has the side's bit; a boundary face is on the side's
// surface when ALL its vertices have the bit (so a face that merely touches the side with an edge is not). Element
// sets: ALL, and one per cell type present: HEX (C3D8 / hex8), WEDGE (C3D6 / penta6), TET (C3D4 / tet4). In the
// files node i+1 is row i of V and element c+1 is cell c. Meshes without "side_mask" get no side sets.
//
// The material frame of each element (material_frame.h) comes from cell data "frame_e1", "frame_e2", "frame_e3" when
// the mesh has them (e.g. read back from an exported file), else from point data "uvw" (a patient hex mesh written by
// `facehex run`); a mesh with neither is exported without orientations.
#include <Eigen/Core>
#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/mesh/material_frame.h"
#include "core/mesh/mesh.h"
#include "core/mesh/sides.h"

namespace facehex {

constexpr std::array<const char*, kNumSides> kSideSetNames = {"LATERAL_NEG_X", "LATERAL_POS_X", "BOTTOM",
                                                              "TOP",           "BONE",          "SKIN"};
constexpr const char* kSurfaceSuffix = "_SURF";
constexpr const char* kAllElementsSet = "ALL";
constexpr std::array<const char*, 3> kFrameArrays = {"frame_e1", "frame_e2", "frame_e3"};

// "HEX", "WEDGE", "TET".
const char* element_set_name(CellType type);

// The solvers (Abaqus/CalculiX, FEBio, Gmsh) number a wedge's first triangle so that its right-hand normal points
// towards the second one, the reverse of VTK (mesh.h); hexes and tets agree with VTK. Node k of a cell in a solver
// file is node solver_node(type, k) of the VTK cell; the map is its own inverse, so it converts both ways.
int solver_node(CellType type, int k);

// Boundary face `face` (an index into cell_faces(type), outward) of cell `cell`.
struct CellFace {
  int cell;
  int face;
};

struct SideSets {
  bool present = false;                                // the mesh has "side_mask"
  std::array<std::vector<int>, kNumSides> nodes;       // ascending vertex ids
  std::array<std::vector<CellFace>, kNumSides> faces;  // ordered by cell, then face
};

SideSets side_sets(const VolumeMesh& mesh);

// Cell types present, in the order Hex, Wedge, Tet, and the cells of one type (ascending).
std::vector<CellType> cell_types_present(const VolumeMesh& mesh);
std::vector<int> cells_of_type(const VolumeMesh& mesh, CellType type);

// The frames to export (see above), or nullopt when the mesh carries neither frames nor "uvw".
std::optional<MaterialFrames> export_frames(const VolumeMesh& mesh);

// For readers of FE files: "side_mask" (#V x 1) from node sets named as above (nullopt when none is), and frames as
// the three cell-data arrays.
std::optional<Eigen::MatrixXd> side_mask_from_node_sets(int num_vertices,
                                                        const std::map<std::string, std::vector<int>>& node_sets);
void attach_frames(VolumeMesh& mesh, const MaterialFrames& frames);

// FE solvers fail on inverted elements, and an element without a frame would silently get the global axes: unless
// allow_inverted, throws facehex::Error(path, ...) naming how many elements are inverted (corner_jacobian.h) or have a
// degenerate frame, and the first of their (1-based) element ids. Elements on the nodes of another are refused even
// then: a solver takes both without a word and doubles the stiffness there, and FaceHex's own meshes never have them.
void check_fe_exportable(const std::string& path, const VolumeMesh& mesh, bool allow_inverted);

// The sets and frames as data arrays, for formats without named sets (.vtu, .vtk): point data "nset_<NAME>" (0 or 1
// per vertex), cell data "surf_<NAME>" (bit f set when local face f of the cell is on the surface; 0 = none) and the
// frame vectors "frame_e1".."frame_e3".
void attach_fe_arrays(VolumeMesh& mesh);

}  // namespace facehex
