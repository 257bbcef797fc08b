#pragma once
// VTK unstructured grids (.vtu XML, .vtk legacy) <-> VolumeMesh. Internal to core/io: use mesh_io.h.
// Writers write to `file` as given (mesh_io.cpp wraps them in write_atomically and validates the mesh first).
#include <set>
#include <string>

#include "core/mesh/mesh.h"

namespace facehex::io {

VolumeMesh read_vtu(const std::string& path);
VolumeMesh read_legacy_vtk(const std::string& path);
// Arrays are written as doubles, those named in `single_precision` as 32-bit floats.
void write_vtu(const std::string& file, const VolumeMesh& mesh,
               const std::set<std::string>& single_precision = {});  // binary, appended, zlib-compressed
void write_legacy_vtk(const std::string& file, const VolumeMesh& mesh,
                      const std::set<std::string>& single_precision = {});  // binary

}  // namespace facehex::io
