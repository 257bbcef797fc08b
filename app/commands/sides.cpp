#include "core/mesh/sides.h"

#include <iostream>

#include "app/cli_args.h"
#include "app/commands/commands.h"
#include "core/fields/constraint_set.h"
#include "core/io/mesh_io.h"
#include "core/mesh/shell_sides.h"
#include "core/util/error.h"

namespace facehex::cli {

int cmd_sides(const Argv& argv) {
  Args args("sides",
            "Labels the six sides of a layered hex-dominant shell (a facial standard) from its element structure and "
            "writes it with the point-data array side_mask. Frame: +x lateral, +y anterior, +z superior.");
  args.positional("MESH", "hex-dominant mesh").option("output", "output .vtu");
  args.option("max-layers", "most element layers through the thickness", "8");
  if (!args.parse(argv)) return 0;
  if (!args.has("output")) throw UsageError("facehex sides", "missing -o OUTPUT");
  check_volume_mesh_output(args.get("output"));
  const int max_layers = args.integer("max-layers", 1, 64);
  VolumeMesh m = read_volume_mesh(args.get("MESH"));
  ShellFrame frame = default_shell_frame(m.V);
  frame.max_layers = max_layers;
  const ShellSides sides = label_shell_sides(m, frame);
  for (int s = 0; s < kNumSides; ++s)
    if (sides.faces_per_side[s] == 0)
      throw Error(args.get("MESH"), std::string("no boundary face found for side ") + kSideNames[s]);
  m.point_data[kSideMaskArray] = sides.side_mask.cast<double>();
  write_volume_mesh(args.get("output"), m);
  std::cout << "boundary faces per side:";
  for (int s = 0; s < kNumSides; ++s) std::cout << " " << kSideNames[s] << " " << sides.faces_per_side[s];
  std::cout << ", openings " << sides.opening_faces << "; vertices on opposite sides left free "
            << sides.conflicting_vertices << "\nwrote " << args.get("output") << "\n";
  return 0;
}

}  // namespace facehex::cli
