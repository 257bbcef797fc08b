#include <iostream>

#include "app/cli_args.h"
#include "app/commands/commands.h"
#include "app/terminal_progress.h"
#include "app/transfer_options.h"
#include "core/fields/parameterization.h"
#include "core/io/mesh_io.h"
#include "core/mesh/mesh_check.h"
#include "core/util/error.h"
#include "core/workflow/standard_setup.h"
#include "core/workflow/transfer.h"

namespace facehex::cli {

int cmd_fields(const Argv& argv) {
  Args args("fields",
            "Computes the three harmonic fields u, v, w of a model with its constraint set, improves their "
            "orthogonality, and writes the parameterized tet mesh (a hex mesh is split into its auxiliary tets).");
  args.positional("MODEL", "tet model, closed surface, or hex-dominant mesh")
      .option("constraints", "constraint-set JSON (default: the six sides from side_mask)")
      .option("output", "output .vtu")
      .option("edge-length", "target edge length (mm) when the model is a closed surface", "2")
      .option("standard-domain", "for a hex mesh: closed (openings filled) or auxiliary (split hexes only)", "closed");
  add_field_options(args);
  if (!args.parse(argv)) return 0;
  if (!args.has("output")) throw UsageError("facehex fields", "missing -o OUTPUT");
  check_volume_mesh_output(args.get("output"));
  const std::string path = args.get("MODEL");
  MeshReadOptions ro;
  ro.target_edge_length = args.number("edge-length", kLeastEdgeLength, kMostEdgeLength);
  const HarmonicFieldsOptions field_opts = field_options(args);
  VolumeMesh mesh = read_volume_mesh(path, ro);
  TetDomain domain;
  if (mesh.is_tet_mesh()) {
    check_and_orient_tet_mesh(mesh, path);
    domain = own_domain(mesh);
  } else {
    domain = standard_domain(mesh, args.get("standard-domain"));
  }
  if (!args.has("constraints") && domain.side_mask.size() == 0)
    throw Error(path, "no constraint set given and the model has no \"side_mask\" array (use --constraints)");
  const ConstraintSet set = args.has("constraints") ? read_constraint_set(args.get("constraints")) : side_constraints();
  TerminalProgress progress;
  const ModelParameterization p =
      parameterize_model(domain.V, domain.T, domain.side_mask, set,
                         args.has("constraints") ? args.get("constraints") : path, field_opts, progress.callback());
  progress.finish();
  VolumeMesh out = parameterized_tet_mesh(p, &mesh);
  if (domain.side_mask.size() == p.V.rows()) out.point_data[kSideMaskArray] = domain.side_mask.cast<double>();
  write_volume_mesh(args.get("output"), out, parameterized_model_writing());
  std::cout << "domain: " << domain.description << " (" << p.T.rows() << " tets)\n"
            << "parameterization: " << p.health.inverted << " inverted, "
            << (p.health.degenerate - p.health.flat_by_constraint) << " degenerate of " << p.health.tets << " tets\n"
            << "gradient angles, mean |90 - angle|: " << p.fields.angles_initial.mean_deviation_from_90
            << " deg before, " << p.fields.angles.mean_deviation_from_90 << " deg after\n"
            << "wrote " << args.get("output") << "\n";
  return p.health.ok() ? 0 : kExitUnusableCells;
}

}  // namespace facehex::cli
