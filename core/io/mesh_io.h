#pragma once
// Reading and writing volume meshes and closed surfaces. The format is chosen from the file name.
//
// Volume meshes (tets, or hex-dominant hex + wedge):
//   read : .vtu, .vtk (legacy), .node/.ele (TetGen; either name), .msh (Gmsh 2.2 and 4.1, ASCII),
//          .node/.elem (ANSYS: see ansys_io.h; chosen when a sibling .elem exists)
//   write: .vtu (all point/cell data attached), .vtk (legacy), .msh (Gmsh 4.1 ASCII)
// Finite-element models with named sets, surfaces and material frames (fe_sets.h, docs/export.md):
//   read and write: .inp (Abaqus / CalculiX, abaqus_io.h), .feb (FEBio 4.0, febio_io.h)
// Closed triangle surfaces (.stl, .obj, .ply, .vtp) given where a volume mesh is expected are tetrahedralized with
// TetGen at MeshReadOptions::target_edge_length.
//
// Every failure is a facehex::Error whose message names the file and the problem (unknown extension, missing file,
// truncated or malformed content, out-of-range node ids, unsupported cell types, not enough memory). Writers never
// leave a partial file (see core/atomic_file.h).
#include <set>
#include <string>
#include <vector>

#include "core/mesh/mesh.h"

namespace facehex {

struct MeshReadOptions {
  double target_edge_length = 2.0;  // mm, for surfaces that get tetrahedralized
};

VolumeMesh read_volume_mesh(const std::string& path, const MeshReadOptions& options = {});

struct MeshWriteOptions {
  // The FE formats (.inp, .feb) refuse meshes with inverted elements (corner_jacobian.h), which no solver accepts,
  // unless this is set; the other formats write any valid mesh so that bad results can be inspected.
  bool allow_inverted = false;
  // Point or cell arrays written as 32-bit floats to .vtu and .vtk (the other formats write no arrays): data for
  // display only, such as per-tet gradients, which are most of a parameterized model's file as doubles.
  std::set<std::string> single_precision_arrays;
};

void write_volume_mesh(const std::string& path, const VolumeMesh& mesh, const MeshWriteOptions& options = {});

// Throws facehex::Error(path, ...) unless a volume mesh can be written to path: a writable extension and a folder that
// exists and takes files. Commands call it before their work, so that a wrong name costs no time.
void check_volume_mesh_output(const std::string& path);

// Reads a triangle surface (.stl, .obj, .ply, .vtp). Polygons are triangulated.
SurfaceMesh read_surface_mesh(const std::string& path);
void write_surface_mesh(const std::string& path, const SurfaceMesh& surface);  // .vtp, .stl, .ply, .obj

bool is_surface_file(const std::string& path);
std::vector<std::string> readable_volume_extensions();
std::vector<std::string> writable_volume_extensions();

}  // namespace facehex
