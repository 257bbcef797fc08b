#include <filesystem>
#include <iostream>
#include <numeric>
#include <sstream>

#include "app/cli_args.h"
#include "app/commands/commands.h"
#include "app/output_folder.h"
#include "app/terminal_progress.h"
#include "app/transfer_options.h"
#include "core/io/mesh_io.h"
#include "core/standard/template_mesh.h"
#include "core/util/resources.h"
#include "core/util/text_file.h"
#include "core/workflow/transfer.h"

namespace facehex::cli {
namespace fs = std::filesystem;

int cmd_template(const Argv& argv) {
  Args args("template",
            "Builds a new standard hex mesh from a reference model (paper 3.1): a grid in the reference's harmonic "
            "parameterization with rows on its feature lines, cells about --cell-size long along the face and "
            "--layers layers from bone to skin, mapped onto the reference and improved until no cell has a scaled "
            "Jacobian below --min-scaled-jacobian where that can be reached. OUT/ gets standard.vtu, constraints.json "
            "and README.md: a folder --standard accepts (or copy it to resources/standards/NAME/).");
  args.positional("REFERENCE", "reference CT volume, tet model or closed surface (default: the bundled sample CT)",
                  false)
      .option("output", "output folder")
      .option("constraints", "constraint set of the reference (default: sides + features at its landmarks)")
      .option("standard", "standard whose feature values the automatic constraints use", "artisynth-refface")
      .option("layers", "hex layers from bone to skin", "3")
      .option("cell-size", "cell length along the face (mm); 0: mean tissue thickness / layers", "0")
      .option("min-scaled-jacobian", "cells below this are improved by the untangler", "0.35")
      .option("edge-length", "target edge length (mm) when the reference is a closed surface or a CT", "2")
      .flag(
          "keep-sharp-corners",
          "keep every side vertex on the reference's surfaces, even where a sharp corner of the reference (a thin fin "
          "of tissue between a cut and the bone) leaves cells below --min-scaled-jacobian");
  add_field_options(args);
  add_segment_options(args);
  if (!args.parse(argv)) return 0;
  if (!args.has("output")) throw UsageError("facehex template", "missing -o OUTPUT_FOLDER");
  std::string input = args.get("REFERENCE");
  if (input.empty()) input = default_ct();
  OutputFolder folder(args.get("output"));
  const fs::path& out_dir = folder.path();

  const PatientSetup reference_setup =
      cli_patient(input, segment_options(args), args.get("constraints"),
                  read_constraint_set(find_standard(args.get("standard")).constraints), "--constraints");
  const VolumeMesh& reference = reference_setup.mesh;
  const ConstraintSet& reference_set = reference_setup.constraints;
  TemplateOptions options;
  options.layers = args.integer("layers", 1, 32);
  options.cell_size = args.number("cell-size", 0.5, 50);
  options.cut_sharp_corners = !args.has("keep-sharp-corners");
  TransferOptions transfer;
  transfer.fields = field_options(args);
  transfer.untangle_options.min_scaled_jacobian = args.number("min-scaled-jacobian");
  TerminalProgress progress;
  TemplateResult t = build_template(reference, reference_set, input, options, transfer, progress.callback());
  progress.finish();

  const MeshQualityReport quality = quality_report(t.mesh, nullptr);
  const DistanceSummary off_surface = side_vertex_distances(t.mesh.V, t.mesh, reference.V, reference.tets());
  std::ostringstream fit;
  fit << "side vertices off the reference's surface: p95 " << fmt("%.2g", off_surface.p95) << " mm, max "
      << fmt("%.2g", off_surface.max) << " mm"
      << (options.cut_sharp_corners ? " (where the repair cut a sharp corner; --keep-sharp-corners keeps them on it)"
                                    : "")
      << "\n";
  const VolumeMesh standard = with_quality(t.mesh);
  write_volume_mesh((out_dir / "standard.vtu").string(), standard);
  write_constraint_set((out_dir / "constraints.json").string(), t.constraints);
  std::ostringstream readme;
  readme << "# Template standard from " << fs::path(input).filename().string() << " (" << t.grid.cells(0) << " x "
         << t.grid.cells(1) << " x " << t.grid.cells(2) << " hexes, mean shape " << quality.summary.shape_mean
         << ")\n\nBuilt by `facehex template` (docs/method.md, template standards) from the reference " << input << " ("
         << reference.num_cells() << " tets; mean bone-to-skin thickness " << t.grid.mean_thickness << " mm), cells "
         << t.grid.cell_size << " mm along the face:\n\n    facehex template"
         << std::accumulate(argv.begin(), argv.end(), std::string(),
                            [](std::string a, const std::string& b) { return a + " " + b; })
         << "\n\n`constraints.json`: the six sides and the reference's feature lines as rows of the grid.\n\n"
         << "```\n"
         << quality_text(quality) << fit.str() << "```\n";
  write_text_file((out_dir / "README.md").string(), readme.str());
  folder.keep();
  std::cout << "grid " << t.grid.cells(0) << " x " << t.grid.cells(1) << " x " << t.grid.cells(2) << " = "
            << t.mesh.num_cells() << " hexes (cell size " << t.grid.cell_size << " mm, mean thickness "
            << t.grid.mean_thickness << " mm)\n"
            << "repair: " << t.run.untangle.bad_before << " cells below the bound before, " << t.run.untangle.bad_after
            << " after\n"
            << quality_text(quality) << fit.str() << "wrote " << out_dir.string()
            << "/: standard.vtu, constraints.json, README.md\n";
  const QualitySummary& q = quality.summary;
  return exit_code(q);
}

}  // namespace facehex::cli
