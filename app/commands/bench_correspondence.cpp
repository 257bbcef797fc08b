#include "app/commands/bench_correspondence.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numeric>
#include <sstream>

#include "app/error_map_png.h"
#include "app/mesh_output.h"
#include "app/output_folder.h"
#include "app/terminal_progress.h"
#include "app/transfer_options.h"
#include "core/evaluation/correspondence_benchmark.h"
#include "core/mesh/sides.h"
#include "core/util/error.h"
#include "core/util/resources.h"
#include "core/util/text_file.h"

namespace facehex::cli {
namespace {

using nlohmann::json;

std::vector<std::string> list(const std::string& text) {
  std::vector<std::string> items = split_commas(text);
  items.erase(std::remove(items.begin(), items.end(), "none"), items.end());
  return items;
}

json to_json(const ErrorSummary& e) {
  return {{"count", e.count}, {"mean", e.mean}, {"p95", e.p95}, {"max", e.max}, {"within_1mm", e.within_1mm}};
}

json to_json(const CorrespondenceError& e) {
  json regions = json::object();
  for (const RegionError& r : e.regions) regions[r.name] = to_json(r.error);
  return {{"all", to_json(e.all)}, {"regions", regions}};
}

json to_json(const CorrespondenceCaseResult& r) {
  json j = {{"kind", r.kind}, {"name", r.name}, {"model", r.model}, {"warp", r.warp}};
  if (!r.failure.empty()) {
    j["failure"] = r.failure;
    return j;
  }
  j.update({{"patient_tets", r.patient_tets},
            {"error_mm", to_json(r.error)},
            {"mapping_error_mm", to_json(r.mapping_error)},
            {"skin_error_split_mm", {{"across", r.skin_split.across}, {"along", r.skin_split.along}}},
            {"warp_mean_mm", r.warp_mean},
            {"moved_by_relaxation_mm", {{"mean", r.moved_by_relaxation_mean}, {"max", r.moved_by_relaxation_max}}},
            {"inverted", r.inverted},
            {"inverted_after_mapping", r.inverted_after_mapping},
            {"folded_parametric_tets", r.folded_parametric_tets},
            {"shape_mean", r.shape_mean},
            {"standard_shape_mean", r.standard_shape_mean},
            {"truth_shape_mean", r.truth_shape_mean},
            {"dihedral_change_mean_deg", r.dihedral_change_mean},
            {"skin_correspondence_used", r.registered_skin ? "registered" : "features"},
            {"registered_failure", r.registered_failure},
            {"seconds", r.seconds},
            {"shape_solver_seconds", r.shape_solver_seconds}});
  // The vertices the error's maximum and tail come from, to look at (ids of the standard's vertices).
  std::vector<int> order(static_cast<size_t>(r.vertex_error.size()));
  std::iota(order.begin(), order.end(), 0);
  const size_t shown = std::min<size_t>(10, order.size());
  std::partial_sort(order.begin(), order.begin() + static_cast<long>(shown), order.end(),
                    [&](int a, int b) { return r.vertex_error(a) > r.vertex_error(b); });
  json largest = json::array();
  for (size_t i = 0; i < shown; ++i) largest.push_back({{"vertex", order[i]}, {"mm", r.vertex_error(order[i])}});
  j["largest_errors"] = largest;
  if (!r.landmark_shift.empty()) j["landmark_shift_mm"] = r.landmark_shift;
  if (!r.cut_shift.empty()) j["cut_shift_mm"] = r.cut_shift;
  if (!r.landmarks_problem.empty()) j["landmarks_problem"] = r.landmarks_problem;
  return j;
}

std::string fmt(const char* format, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, x);
  return buf;
}

std::string triple(const ErrorSummary& e) {
  return fmt("%.2f", e.mean) + " / " + fmt("%.2f", e.p95) + " / " + fmt("%.1f", e.max);
}

// The mean over the regions whose name starts with `prefix`, the worst of them.
std::string worst_region(const CorrespondenceError& e, const std::string& prefix) {
  double worst = -1;
  std::string name;
  for (const RegionError& r : e.regions)
    if (r.name.rfind(prefix, 0) == 0 && r.error.count > 0 && r.error.mean > worst) {
      worst = r.error.mean;
      name = r.name.substr(prefix.size());
    }
  return worst < 0 ? "–" : fmt("%.2f", worst) + (name.empty() ? "" : " (" + name + ")");
}

std::string region_mean(const CorrespondenceError& e, const std::string& name) {
  for (const RegionError& r : e.regions)
    if (r.name == name) return fmt("%.2f", r.error.mean);
  return "–";
}

// The cases' input shifts (CorrespondenceCaseResult::landmark_shift, cut_shift, landmarks_problem); empty when no case
// has any (true landmarks only).
std::string input_shifts_markdown(const std::vector<CorrespondenceCaseResult>& results) {
  std::ostringstream md, problems;
  bool any = false;
  for (const CorrespondenceCaseResult& r : results) {
    if (r.landmark_shift.empty() && r.cut_shift.empty() && r.landmarks_problem.empty()) continue;
    if (!r.landmarks_problem.empty()) problems << "- " << r.name << ": no landmarks (" << r.landmarks_problem << ")\n";
    if (!any)
      md << "\nWhat the landmark finder found on each model against where it should (mm): on a self-map or a "
            "deformation the standard's own landmarks moved by the warp; on a warped CT the warp of what it, and the "
            "segmentation, found on the original CT (cuts signed, along the plane's axis):\n\n"
         << "| case | landmarks mean | worst landmark | top cut | bottom cut | posterior cut | mid-sagittal plane |\n"
         << "| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n";
    any = true;
    double sum = 0, worst = -1;
    std::string worst_name;
    for (const auto& [name, shift] : r.landmark_shift) {
      sum += shift;
      if (shift > worst) worst = shift, worst_name = name;
    }
    const auto cut = [&](const std::string& name) {
      const auto it = r.cut_shift.find(name);
      return it == r.cut_shift.end() ? std::string("–") : fmt("%+.1f", it->second);
    };
    md << "| " << r.name << " | "
       << (!r.landmarks_problem.empty() ? "none (below)"
           : r.landmark_shift.empty()   ? "–"
                                        : fmt("%.2f", sum / static_cast<double>(r.landmark_shift.size())))
       << " | " << (worst < 0 ? "–" : fmt("%.1f", worst) + " (" + worst_name + ")") << " | " << cut("top") << " | "
       << cut("bottom") << " | " << cut("posterior") << " | " << cut("mid-sagittal") << " |\n";
  }
  if (!problems.str().empty()) md << "\n" << problems.str();
  return md.str();
}

std::string markdown(const std::vector<CorrespondenceCaseResult>& results, const std::string& setting) {
  std::ostringstream md;
  md << "Transfer options: " << setting << ".\n\n"
     << "| case | model tets | error mean / p95 / max (mm) | within 1 mm | plain mapping mean (mm) | landmarks | "
        "worst opening rim | skin | skin: across / along | bone | inner face | warp moves (mm) | folded parametric "
        "tets | inverted: mapped, result | "
        "shape / standard's | the truth's shape / standard's | dihedral change (°) | time (s): case, relaxation + "
        "repair |\n"
     << "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | "
        "---: | ---: | ---: |\n";
  for (const CorrespondenceCaseResult& r : results) {
    md << "| " << r.kind << ": " << r.name
       << (r.registered_failure.empty() ? "" : " (feature lines: the registered skin failed)") << " | ";
    if (!r.failure.empty()) {
      md << "failed" << (r.warp.empty() ? "" : " (" + r.warp + ")") << ": " << r.failure << " |||||||||||||||||\n";
      continue;
    }
    md << r.patient_tets << " | " << triple(r.error.all) << " | " << fmt("%.0f %%", 100 * r.error.all.within_1mm)
       << " | " << fmt("%.2f", r.mapping_error.all.mean) << " | " << region_mean(r.error, "landmarks") << " | "
       << worst_region(r.error, "rim: ") << " | " << region_mean(r.error, "skin") << " | "
       << fmt("%.2f", r.skin_split.across) << " / " << fmt("%.2f", r.skin_split.along) << " | "
       << region_mean(r.error, "bone") << " | " << region_mean(r.error, "inner face") << " | "
       << fmt("%.2f", r.warp_mean) << " | " << r.folded_parametric_tets << " | " << r.inverted_after_mapping << ", "
       << r.inverted << " | " << fmt("%.3f", r.shape_mean / r.standard_shape_mean) << " | "
       << fmt("%.3f", r.truth_shape_mean / r.standard_shape_mean) << " | " << fmt("%.1f", r.dihedral_change_mean)
       << " | " << fmt("%.0f", r.seconds) << ", " << fmt("%.1f", r.shape_solver_seconds) << " |\n";
  }
  md << input_shifts_markdown(results);
  return md.str();
}

// The skin error of the worst case (by mean) of each kind.
void write_skin_error_png(const std::string& path, const StandardSetup& standard,
                          const std::vector<CorrespondenceCaseResult>& results) {
  const Eigen::VectorXi mask = side_mask_of(standard.mesh);
  std::vector<int> skin;
  for (int v = 0; v < mask.size(); ++v)
    if (mask(v) & side_bit(W1)) skin.push_back(v);
  std::vector<ErrorMapPanel> panels;
  for (const std::string kind : {"self-map", "deformation", "ct"}) {
    const CorrespondenceCaseResult* worst = nullptr;
    for (const CorrespondenceCaseResult& r : results)
      if (r.kind == kind && r.failure.empty() && (!worst || r.error.all.mean > worst->error.all.mean)) worst = &r;
    if (!worst) continue;
    ErrorMapPanel panel;
    panel.title = "worst " + kind + ": " + worst->name + fmt(" (mean %.2f mm)", worst->error.all.mean);
    panel.points.resize(static_cast<Eigen::Index>(skin.size()), 3);
    panel.error.resize(static_cast<Eigen::Index>(skin.size()));
    for (size_t i = 0; i < skin.size(); ++i) {
      panel.points.row(static_cast<Eigen::Index>(i)) = standard.mesh.V.row(skin[i]);
      panel.error(static_cast<Eigen::Index>(i)) = worst->vertex_error(skin[i]);
    }
    panels.push_back(std::move(panel));
  }
  write_error_map_png(path, "Correspondence error on the standard's skin, seen from the front", panels, 5.0);
}

}  // namespace

void add_correspondence_options(Args& args) {
  args.flag("correspondence",
            "instead: the correspondence benchmark, known-answer transfers of the standard (self-maps onto re-meshings "
            "of its volume, the same under smooth warps, warped CTs); writes OUT/correspondence.md, .json and "
            "correspondence_skin_error.png")
      .option("output", "with --correspondence: the report's folder")
      .option("models", "with --correspondence: self-map models: split, open-E, closed-E (E: TetGen edge, mm)",
              "split,open-3,closed-3")
      .option("deformation-models",
              "with --correspondence: the models the warps deform: models of the standard as --models names them, or "
              "patients' tet model files (e.g. a segmented CT's model; the answer: the warp applied to the transfer "
              "onto the model as it is)",
              "closed-3")
      .option("warps", "with --correspondence: random-SEED, chin, nose (none: no deformation)",
              "random-1,random-2,chin,nose")
      .option("cts", "with --correspondence: CT files warped for equivariance (default: the bundled CT; none: no CT)")
      .option("ct-seeds", "with --correspondence: seeds of the CT warps", "1,2")
      .option("ct-ranges",
              "with --correspondence: the CT warps' largest scale change, shear, bump (mm), turn about the "
              "vertical and, optionally, pitch about the lateral axis and roll about the front-to-back axis (degrees)",
              "0.08,0.04,4,0")
      .flag("keep-patients",
            "with --correspondence: keep each case's patient in the report's folder: a model as "
            "KIND-CASE.vtu (e.g. deformation-nose-on-closed-3.vtu), a warped CT as STEM-warp-SEED.mha")
      .flag("true-landmarks",
            "with --correspondence: a model's feature constraints at the standard's landmarks moved by the warp (a "
            "patient model's at its own), and a warped CT's at the original CT's landmarks moved by the warp, not at "
            "those found on it (separates the landmark finder's error)")
      .flag("mapping-only", "with --correspondence: the plain mapping alone, no relaxation and no repair (quick)");
}

int correspondence_bench(const Args& args) {
  if (!args.has("output")) throw UsageError("facehex bench --correspondence", "missing -o OUTPUT_FOLDER");
  check_transfer_options(args);
  CorrespondenceBenchmarkOptions options;
  options.transfer = transfer_options(args);
  if (args.has("mapping-only")) options.transfer.shape_relaxation = options.transfer.repair_folds = false;
  options.true_landmarks = args.has("true-landmarks");
  options.segment = segment_options(args);
  options.models = list(args.get("models"));
  options.self_maps = !options.models.empty();
  options.deformation_models = list(args.get("deformation-models"));
  options.warps = list(args.get("warps"));
  options.cts = args.has("cts") ? list(args.get("cts")) : std::vector<std::string>{default_ct()};
  options.ct_seeds.clear();
  for (const std::string& s : list(args.get("ct-seeds"))) {
    try {
      options.ct_seeds.push_back(std::stoull(s));
    } catch (const std::exception&) {
      throw UsageError("--ct-seeds", "expects comma-separated whole numbers, got '" + args.get("ct-seeds") + "'");
    }
  }
  std::vector<double> r;
  bool numbers = true;
  for (const std::string& v : list(args.get("ct-ranges"))) {
    char* end = nullptr;
    r.push_back(std::strtod(v.c_str(), &end));
    numbers = numbers && !v.empty() && *end == '\0' && std::isfinite(r.back()) && r.back() >= 0;
  }
  if (!numbers || r.size() < 4 || r.size() > 6 || r[0] >= 0.5 || r[1] >= 0.5 || r[2] > 20 || r[3] > 45 ||
      (r.size() >= 5 && r[4] > 30) || (r.size() == 6 && r[5] > 30))
    throw UsageError("--ct-ranges",
                     "expects SCALE,SHEAR,BUMP,TURN[,PITCH[,ROLL]] with scale and shear below 0.5, a bump of at most "
                     "20 mm, a turn of at most 45 degrees and a pitch and a roll of at most 30, got '" +
                         args.get("ct-ranges") + "'");
  options.ct_ranges.max_scale = r[0], options.ct_ranges.max_shear = r[1], options.ct_ranges.max_bump = r[2];
  options.ct_ranges.max_turn = r[3];
  if (r.size() >= 5) options.ct_ranges.max_pitch = r[4];
  if (r.size() == 6) options.ct_ranges.max_roll = r[5];
  for (const std::string& ct : options.cts)
    if (!std::filesystem::exists(ct)) throw Error(ct, "no such CT file (--cts)");
  OutputFolder folder(args.get("output"));
  if (args.has("keep-patients")) options.keep_patients = args.get("output");
  const StandardSetup standard = standard_setup(args);
  TerminalProgress progress;
  const auto results = run_correspondence_benchmark(
      standard, options,
      [&](int index, int count, const std::string& name) {
        progress.finish();
        std::cerr << "[" << index + 1 << "/" << count << "] " << name << "\n";
      },
      progress.callback(),
      [&](const CorrespondenceCaseResult& r) {
        progress.finish();
        if (!r.failure.empty())
          std::cerr << "  failed: " << r.failure << "\n";
        else
          std::cerr << "  error mean / p95 / max " << triple(r.error.all) << " mm (plain mapping "
                    << triple(r.mapping_error.all) << "), " << r.folded_parametric_tets << " folded parametric tets, "
                    << r.inverted << " inverted cells, " << fmt("%.0f s", r.seconds) << "\n";
      });
  progress.finish();

  const std::string setting =
      (args.has("mapping-only") ? std::string("`--mapping-only`")
                                : "`--shape-relaxation " + args.get("shape-relaxation") + "`, `--shape-tether " +
                                      args.get("shape-tether") + "`") +
      ", `--skin-correspondence " + args.get("skin-correspondence") + "`" +
      (options.true_landmarks ? ", `--true-landmarks`" : "") + ", `--standard-domain " + args.get("standard-domain") +
      "`, standard " + standard.name + " with " +
      (args.has("standard-constraints") ? "`--standard-constraints " + args.get("standard-constraints") + "`"
                                        : std::string("its bundled constraints"));
  json report = {{"standard", standard.name},
                 {"shape_relaxation", args.get("shape-relaxation")},
                 {"shape_tether", args.get("shape-tether")},
                 {"skin_correspondence", args.get("skin-correspondence")},
                 {"standard_domain", args.get("standard-domain")},
                 {"standard_constraints", standard.constraints_path},
                 {"mapping_only", args.has("mapping-only")},
                 {"true_landmarks", options.true_landmarks},
                 {"cases", json::array()}};
  for (const auto& r : results) report["cases"].push_back(to_json(r));
  write_json(folder.file("correspondence.json").string(), report);
  write_text_file(folder.file("correspondence.md").string(), markdown(results, setting));
  write_skin_error_png(folder.file("correspondence_skin_error.png").string(), standard, results);
  folder.keep();
  std::cout << markdown(results, setting) << "report in " << folder.path().string()
            << "/: correspondence.md, correspondence.json, correspondence_skin_error.png\n";
  for (const auto& r : results)
    if (!r.failure.empty()) return 1;
  return 0;
}

}  // namespace facehex::cli
