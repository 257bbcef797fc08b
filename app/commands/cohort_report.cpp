#include <iostream>
#include <set>

#include "app/category_png.h"
#include "app/cli_args.h"
#include "app/commands/commands.h"
#include "app/histogram_png.h"
#include "app/output_folder.h"
#include "core/util/error.h"
#include "core/util/text_file.h"
#include "core/workflow/cohort.h"

namespace facehex::cli {
namespace {

// One colour per patient, repeating after ten (matplotlib's "tab10").
const std::vector<Rgb> kPalette = {{31, 119, 180}, {255, 127, 14},  {44, 160, 44},   {214, 39, 40},  {148, 103, 189},
                                   {140, 86, 75},  {227, 119, 194}, {127, 127, 127}, {188, 189, 34}, {23, 190, 207}};
const Rgb kOk = {31, 119, 180}, kFailed = {214, 39, 40};

// The plots of cohort.md, in `folder`: file name -> caption.
std::vector<std::pair<std::string, std::string>> write_cohort_plots(const OutputFolder& folder,
                                                                    const std::vector<CohortPatient>& patients) {
  std::vector<std::pair<std::string, std::string>> plots;
  HistogramPlot dihedral;
  dihedral.title = "Change of the dihedral angles against the standard, per patient";
  dihedral.x_label = "absolute change of a cell's dihedral angle (degrees; the last bin holds all above)";
  for (int e = 0; e <= 45; ++e) dihedral.edges.push_back(2.0 * e);
  dihedral.overlaid = true;
  CategoryPlot shape;
  shape.title = "Element shape per patient (box: quartiles and median; whiskers: least and greatest)";
  shape.y_label = "shape (1: ideal cell)";
  for (size_t i = 0; i < patients.size(); ++i) {
    const CohortPatient& p = patients[i];
    if (!p.mesh) continue;
    const Rgb& color = kPalette[i % kPalette.size()];
    dihedral.series.push_back({p.id, color,
                               percent_histogram(Eigen::Map<const Eigen::VectorXd>(
                                                     p.mesh->dihedral_changes.data(),
                                                     static_cast<Eigen::Index>(p.mesh->dihedral_changes.size())),
                                                 dihedral.edges)});
    shape.items.push_back({p.id, color, p.mesh->shapes});
    shape.reference = p.mesh->standard_shape_mean;
  }
  if (!dihedral.series.empty()) {
    write_histogram_png(folder.file("cohort_dihedral_change.png").string(), dihedral);
    plots.emplace_back("cohort_dihedral_change.png", "dihedral-angle change against the standard, per patient");
    shape.reference_label = "standard's mean shape";
    write_box_plot_png(folder.file("cohort_shape.png").string(), shape);
    plots.emplace_back("cohort_shape.png", "element shape per patient");
  }
  CategoryPlot time;
  time.title = "Wall time per patient (all its steps)";
  time.y_label = "seconds";
  time.legend = {{"ok", kOk}, {"failed", kFailed}};
  for (const CohortPatient& p : patients) time.items.push_back({p.id, p.ok() ? kOk : kFailed, {p.seconds}});
  write_bar_chart_png(folder.file("cohort_time.png").string(), time);
  plots.emplace_back("cohort_time.png", "wall time per patient");
  return plots;
}

}  // namespace

int cmd_cohort_report(const Argv& argv) {
  Args args("cohort-report",
            "The report of a cohort meshed by the cohort workflow (workflow/Snakefile, docs/cohorts.md): one row per "
            "patient from the status file of its last step and its report.json, summary statistics and plots. "
            "OUT/ gets cohort.md, cohort.json, cohort.csv and cohort_*.png.");
  args.positional("STATUS", "a patient's status file (facehex-cohort-status JSON); one per patient")
      .last_positional_repeats()
      .option("output", "output folder");
  if (!args.parse(argv)) return 0;
  if (!args.has("output")) throw UsageError("facehex cohort-report", "missing -o OUTPUT_FOLDER");
  std::vector<std::string> paths = {args.get("STATUS")};
  paths.insert(paths.end(), args.rest().begin(), args.rest().end());
  std::vector<CohortPatient> patients;
  std::set<std::string> ids;
  for (const std::string& path : paths) {
    patients.push_back(read_cohort_patient(path));
    if (!ids.insert(patients.back().id).second)
      throw Error(path, "patient id '" + patients.back().id + "' appears twice in the cohort");
  }
  OutputFolder folder(args.get("output"));
  const CohortSummary summary = summarize_cohort(patients);
  const auto plots = write_cohort_plots(folder, patients);
  write_text_file(folder.file("cohort.json").string(), cohort_json(patients, summary).dump(2) + "\n");
  write_text_file(folder.file("cohort.csv").string(), cohort_csv(patients));
  write_text_file(folder.file("cohort.md").string(), cohort_markdown(patients, summary, plots));
  folder.keep();
  std::cout << summary.ok << " of " << summary.patients << " patients ok; wrote " << folder.file("cohort.md").string()
            << ", cohort.json, cohort.csv and " << plots.size() << " plots\n";
  return 0;
}

}  // namespace facehex::cli
