// The public entry points of mesh_io.h: pick the format from the file name and hand over to its reader or writer.
#include "core/io/mesh_io.h"

#include <algorithm>
#include <filesystem>
#include <functional>

#include "core/io/abaqus_io.h"
#include "core/io/ansys_io.h"
#include "core/io/fe_sets.h"
#include "core/io/febio_io.h"
#include "core/io/gmsh_io.h"
#include "core/io/io_util.h"
#include "core/io/tetgen_io.h"
#include "core/io/vtk_mesh_io.h"
#include "core/tetgen/tetrahedralize.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/util/memory_errors.h"

namespace facehex {

namespace {

const std::vector<std::string> kSurfaceExtensions = {".stl", ".obj", ".ply", ".vtp"};

std::string join(const std::vector<std::string>& items) {
  std::string s;
  for (const std::string& item : items) s += (s.empty() ? "" : ", ") + item;
  return s;
}

std::string stem_with(const std::string& path, const std::string& ext) {
  return std::filesystem::path(path).filename().replace_extension(ext).string();
}

// .node is shared by TetGen (.node + .ele) and ANSYS (.node + .elem): the sibling decides.
VolumeMesh read_node_pair(const std::string& path, const std::string& ext) {
  if (ext == ".elem") {
    const std::string node = io::find_sibling(path, ".node");
    if (node.empty()) throw Error(path, "ANSYS element file without its node file " + stem_with(path, ".node"));
    return read_ansys_mesh(node, path);
  }
  if (ext == ".ele") {
    const std::string node = io::find_sibling(path, ".node");
    if (node.empty()) throw Error(path, "TetGen element file without its node file " + stem_with(path, ".node"));
    return io::read_tetgen(node, path);
  }
  if (const std::string elem = io::find_sibling(path, ".elem"); !elem.empty()) return read_ansys_mesh(path, elem);
  if (const std::string ele = io::find_sibling(path, ".ele"); !ele.empty()) return io::read_tetgen(path, ele);
  throw Error(path, "node file without elements: found neither " + stem_with(path, ".ele") + " (TetGen) nor " +
                        stem_with(path, ".elem") + " (ANSYS)");
}

}  // namespace

bool is_surface_file(const std::string& path) {
  const std::string ext = io::lower_extension(path);
  return std::find(kSurfaceExtensions.begin(), kSurfaceExtensions.end(), ext) != kSurfaceExtensions.end();
}

std::vector<std::string> readable_volume_extensions() {
  std::vector<std::string> exts = {".vtu", ".vtk", ".msh", ".node", ".ele", ".elem", ".inp", ".feb"};
  exts.insert(exts.end(), kSurfaceExtensions.begin(), kSurfaceExtensions.end());  // tetrahedralized on reading
  return exts;
}

std::vector<std::string> writable_volume_extensions() { return {".vtu", ".vtk", ".msh", ".inp", ".feb"}; }

namespace {

VolumeMesh read_volume_mesh_of_kind(const std::string& path, const MeshReadOptions& options) {
  const std::string ext = io::lower_extension(path);
  const std::vector<std::string> readable = readable_volume_extensions();
  if (std::find(readable.begin(), readable.end(), ext) == readable.end()) {
    throw Error(path, "unknown mesh file extension '" + ext + "' (readable: " + join(readable) + ")");
  }
  io::check_readable_file(path);
  if (ext == ".vtu") return io::read_vtu(path);
  if (ext == ".vtk") return io::read_legacy_vtk(path);
  if (ext == ".msh") return io::read_gmsh(path);
  if (ext == ".inp") return io::read_abaqus(path);
  if (ext == ".feb") return io::read_febio(path);
  if (ext == ".node" || ext == ".ele" || ext == ".elem") return read_node_pair(path, ext);

  const SurfaceMesh surface = read_surface_mesh(path);
  TetrahedralizeOptions tet_options;
  tet_options.target_edge_length = options.target_edge_length;
  try {
    return tetrahedralize(surface, tet_options).mesh;
  } catch (const Error& e) {
    throw Error(path, std::string("cannot tetrahedralize the surface: ") + e.what());
  }
}

}  // namespace

VolumeMesh read_volume_mesh(const std::string& path, const MeshReadOptions& options) {
  return naming_memory_errors(path, "read it", [&] { return read_volume_mesh_of_kind(path, options); });
}

void check_volume_mesh_output(const std::string& path) {
  const std::vector<std::string> writable = writable_volume_extensions();
  const std::string ext = io::lower_extension(path);
  if (std::find(writable.begin(), writable.end(), ext) == writable.end())
    throw Error(path, "cannot write volume meshes as '" + ext + "' (writable: " + join(writable) + ")");
  check_writable_file(path);
}

void write_volume_mesh(const std::string& path, const VolumeMesh& mesh, const MeshWriteOptions& options) {
  const std::string ext = io::lower_extension(path);
  const std::set<std::string>& single = options.single_precision_arrays;
  std::function<void(const std::string&, const VolumeMesh&)> write;
  if (ext == ".vtu") write = [&](const std::string& f, const VolumeMesh& m) { io::write_vtu(f, m, single); };
  if (ext == ".vtk") write = [&](const std::string& f, const VolumeMesh& m) { io::write_legacy_vtk(f, m, single); };
  if (ext == ".msh") write = io::write_gmsh;
  if (ext == ".inp") write = io::write_abaqus;
  if (ext == ".feb") write = io::write_febio;
  if (!write) check_volume_mesh_output(path);
  io::check_volume_mesh(path, mesh);
  if (ext == ".inp" || ext == ".feb") check_fe_exportable(path, mesh, options.allow_inverted);
  write_atomically(path, [&](const std::string& tmp) { write(tmp, mesh); });
}

}  // namespace facehex
