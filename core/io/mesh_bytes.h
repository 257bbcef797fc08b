#pragma once
// A VolumeMesh as bytes and back, to pass it from a child process (core/util/child_process.h) to its parent: the
// parent's copy is the same mesh, bit for bit. Not a file format: both ends are the same build.
#include <vector>

#include "core/mesh/mesh.h"

namespace facehex::io {

std::vector<char> to_bytes(const VolumeMesh& mesh);
std::vector<char> to_bytes(const SurfaceMesh& surface);
// Throw Error(subject, ...) if the bytes are not a whole mesh.
VolumeMesh mesh_from_bytes(const std::vector<char>& bytes, const std::string& subject);
SurfaceMesh surface_from_bytes(const std::vector<char>& bytes, const std::string& subject);

}  // namespace facehex::io
