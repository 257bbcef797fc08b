#include <filesystem>
#include <iostream>

#include "app/cli_args.h"
#include "app/commands/commands.h"
#include "app/commands/compare.h"
#include "app/mesh_output.h"
#include "app/transfer_options.h"
#include "core/io/mesh_io.h"
#include "core/segment/patient_input.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/util/resources.h"
#include "core/workflow/transfer.h"

namespace facehex::cli {
namespace {

// The mesh and, with --report, its report: both or neither (a report that cannot be written takes the mesh back).
void write_with_report(const Args& args, const VolumeMesh& hex, const nlohmann::json& report) {
  write_volume_mesh(args.get("output"), hex, write_options(args));
  if (!args.has("report")) return;
  try {
    write_json(args.get("report"), report);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(args.get("output"), ignored);
    throw;
  }
}

}  // namespace

int cmd_map(const Argv& argv) {
  Args args("map",
            "Maps a standard hex mesh onto a patient tet model through their harmonic parameterizations "
            "(or, with --method mesh-matching, by the elastic-registration baseline of docs/method.md).");
  args.option("patient", "patient tet model or closed surface")
      .option("patient-constraints",
              "constraint set of the patient (default: NAME.json or constraints.json beside it, else automatic)")
      .option("output", "output hex mesh (.vtu, .vtk, .msh, .inp, .feb)")
      .option("report", "write the JSON report here too")
      .option("method", "harmonic (the paper's method) or mesh-matching (the baseline it is compared with)", "harmonic")
      .flag("force-export", kForceExportHelp);
  add_transfer_options(args);
  if (!args.parse(argv)) return 0;
  if (!args.has("patient") || !args.has("output")) throw UsageError("facehex map", "needs --patient and -o OUTPUT");
  check_volume_mesh_output(args.get("output"));
  if (args.has("report")) check_writable_file(args.get("report"));
  if (args.get("method") == "mesh-matching") {
    // The baseline registers the surfaces: it needs no constraints, and the standard no parameterization domain.
    const BundledModel standard = find_standard(args.get("standard"));
    const PatientTetModel patient = read_patient_model(args.get("patient"), segment_options(args));
    MatchingOutputs out =
        execute_mesh_matching(read_volume_mesh(standard.mesh), standard.mesh, patient.mesh, args.get("patient"));
    write_with_report(args, with_quality(out.result.hex), mesh_matching_report(out));
    std::cout << mesh_matching_summary_text(out) << "wrote " << args.get("output") << "\n";
    return exit_code(out.metrics.quality.summary);
  }
  if (args.get("method") != "harmonic")
    throw UsageError("--method", "expects harmonic or mesh-matching, got '" + args.get("method") + "'");
  const CliTransfer t =
      cli_transfer(args, args.get("patient"), args.get("patient-constraints"), "--patient-constraints");
  const TransferResult& r = t.result;
  nlohmann::json report = run_report(r.run, r.standard_quality, r.plain_mapping_quality, r.patient_quality, r.distance);
  report["skin_correspondence"] = skin_correspondence_json(r);
  report["feature_landing"] = feature_landing_json(r.landing);
  write_with_report(args, r.patient_hex, report);
  std::cout << skin_correspondence_text(r)
            << run_summary_text(r.run, r.standard_quality, r.plain_mapping_quality, r.patient_quality, r.distance)
            << feature_landing_text(r.landing) << "wrote " << args.get("output") << "\n";
  return exit_code(r.patient_quality.summary);
}

}  // namespace facehex::cli
