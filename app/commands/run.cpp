#include <algorithm>
#include <filesystem>
#include <iostream>

#include "app/cli_args.h"
#include "app/commands/commands.h"
#include "app/mesh_output.h"
#include "app/output_folder.h"
#include "app/transfer_options.h"
#include "core/face/landmark_file.h"
#include "core/io/mesh_io.h"
#include "core/util/error.h"
#include "core/util/resources.h"
#include "core/workflow/transfer.h"

namespace facehex::cli {
namespace fs = std::filesystem;

int cmd_run(const Argv& argv) {
  Args args("run",
            "End to end: the patient (a CT is segmented first; default: the bundled sample CT) is parameterized with "
            "its constraints (--constraints, else NAME.json or constraints.json beside a mesh file, else automatic: "
            "six sides and the facial features at its landmarks), the standard mapped onto it, and OUT/ gets "
            "patient_model.vtu, standard_hex.vtu, patient_hex.vtu and report.json.");
  args.positional("INPUT", "patient CT volume, tet model or closed surface", false)
      .option("output", "output folder")
      .option("constraints",
              "constraint set of the patient (default: NAME.json or constraints.json beside it, else automatic)")
      .option("landmarks",
              "facial landmarks of the patient (.json, or 3D Slicer .mrk.json) to place the feature constraints at "
              "instead of those found; the ones used are written to OUT/landmarks.json")
      .option("export", "also write OUT/patient_hex.EXT for each listed format, e.g. feb,inp,msh (docs/export.md)")
      .flag("force-export", kForceExportHelp);
  add_transfer_options(args);
  if (!args.parse(argv)) return 0;
  if (!args.has("output")) throw UsageError("facehex run", "missing -o OUTPUT_FOLDER");
  const std::vector<std::string> exports = export_formats(args.get("export"));
  std::string input = args.get("INPUT");
  const std::string constraints = args.get("constraints");
  if (input.empty()) {
    input = default_ct();
    std::cerr << "no input given: running the bundled demo, the whole chain from the sample CT " << input << "\n";
  }
  check_transfer_options(args);  // option errors before any folder
  OutputFolder folder(args.get("output"));
  const fs::path& out_dir = folder.path();
  // A report only once the run is complete; the exports of an earlier run that this one does not make are removed.
  std::vector<std::string> stale = {"report.json"};
  for (const char* ext : {"feb", "inp", "msh", "vtk"})
    if (std::find(exports.begin(), exports.end(), ext) == exports.end())
      stale.push_back(std::string("patient_hex.") + ext);
  for (const std::string& name : folder.remove_stale(stale))
    if (name != "report.json") std::cerr << "removed " << (out_dir / name).string() << " of an earlier run\n";

  const CliTransfer t = cli_transfer(args, input, constraints, "--constraints", args.get("landmarks"));
  if (t.patient.landmarks)
    write_landmark_file((out_dir / "landmarks.json").string(), named_landmarks(*t.patient.landmarks),
                        t.patient.landmarks->scan_frame);
  const TransferResult& r = t.result;
  write_volume_mesh((out_dir / "patient_model.vtu").string(), parameterized_tet_mesh(r.run.patient, &t.patient.mesh),
                    parameterized_model_writing());
  write_volume_mesh((out_dir / "standard_hex.vtu").string(), standard_with_fields(t.standard.mesh, r.run.standard));
  write_volume_mesh((out_dir / "patient_hex.vtu").string(), r.patient_hex);
  std::vector<std::string> written = {"patient_model.vtu", "standard_hex.vtu", "patient_hex.vtu"};
  for (const std::string& ext : exports) {
    const std::string path = (out_dir / ("patient_hex." + ext)).string();
    write_volume_mesh(path, r.patient_hex, write_options(args));
    written.push_back("patient_hex." + ext);
  }
  nlohmann::json report = run_report(r.run, r.standard_quality, r.plain_mapping_quality, r.patient_quality, r.distance);
  report["inputs"] = {
      {"patient", input}, {"patient_constraints", t.patient.constraints_path}, {"standard", t.standard.name}};
  report["segmentation"] = segmentation_json(t.patient.segmentation);
  report["landmarks"] = landmarks_json(t.patient.landmarks);
  report["skin_correspondence"] = skin_correspondence_json(r);
  report["feature_landing"] = feature_landing_json(r.landing);
  report["outputs"] = folder.completion_record(written);
  write_json((out_dir / "report.json").string(), report);
  std::cout << skin_correspondence_text(r)
            << run_summary_text(r.run, r.standard_quality, r.plain_mapping_quality, r.patient_quality, r.distance)
            << feature_landing_text(r.landing) << "outputs in " << out_dir.string()
            << "/: patient_model.vtu, standard_hex.vtu, patient_hex.vtu";
  for (const std::string& ext : exports) std::cout << ", patient_hex." << ext;
  std::cout << ", report.json (written last: its \"outputs\" record lists every file with its SHA-256)\n";
  folder.keep();
  const QualitySummary& q = r.patient_quality.summary;
  if (exit_code(q) != 0)
    std::cerr << "warning: " << q.inverted << " inverted and " << q.degenerate
              << " degenerate cells remain in patient_hex.vtu (cell data scaled_jacobian shows where)\n";
  return exit_code(q);
}

}  // namespace facehex::cli
