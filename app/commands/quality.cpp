#include <iostream>

#include "app/cli_args.h"
#include "app/commands/commands.h"
#include "core/io/mesh_io.h"
#include "core/workflow/report.h"
#include "core/workflow/transfer.h"

namespace facehex::cli {

int cmd_quality(const Argv& argv) {
  Args args("quality", "Element quality of a hex-dominant mesh; with --reference, the dihedral-angle distortion.");
  args.positional("MESH", "hex-dominant mesh")
      .option("reference", "the standard it was mapped from")
      .flag("json", "print JSON");
  if (!args.parse(argv)) return 0;
  const VolumeMesh m = read_volume_mesh(args.get("MESH"));
  VolumeMesh reference;
  if (args.has("reference")) reference = read_volume_mesh(args.get("reference"));
  const MeshQualityReport q = quality_report(m, args.has("reference") ? &reference : nullptr);
  if (args.has("json"))
    std::cout << to_json(q).dump(2) << "\n";
  else
    std::cout << args.get("MESH") << "\n" << quality_text(q);
  return exit_code(q.summary);
}

}  // namespace facehex::cli
