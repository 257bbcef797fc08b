#include <iostream>

#include "app/cli_args.h"
#include "app/commands/commands.h"
#include "app/mesh_output.h"
#include "app/transfer_options.h"
#include "core/io/mesh_io.h"

namespace facehex::cli {

int cmd_convert(const Argv& argv) {
  Args args("convert", "Converts a mesh to another format (a closed surface is tetrahedralized first).");
  args.positional("IN", "input mesh").positional("OUT", "output mesh (.vtu, .vtk, .msh, .inp, .feb)");
  args.option("edge-length", "target edge length (mm) for surfaces", "2").flag("force-export", kForceExportHelp);
  if (!args.parse(argv)) return 0;
  check_volume_mesh_output(args.get("OUT"));
  MeshReadOptions ro;
  ro.target_edge_length = args.number("edge-length", kLeastEdgeLength, kMostEdgeLength);
  const VolumeMesh m = read_volume_mesh(args.get("IN"), ro);
  write_volume_mesh(args.get("OUT"), m, write_options(args));
  std::cout << "wrote " << args.get("OUT") << " (" << m.num_vertices() << " vertices, " << m.num_cells() << " cells)\n";
  return 0;
}

}  // namespace facehex::cli
