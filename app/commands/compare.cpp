#include "app/commands/compare.h"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <set>
#include <sstream>

#include "app/cli_args.h"
#include "app/commands/commands.h"
#include "app/histogram_png.h"
#include "app/output_folder.h"
#include "app/terminal_progress.h"
#include "app/transfer_options.h"
#include "core/util/error.h"
#include "core/util/resources.h"
#include "core/util/text_file.h"

namespace facehex::cli {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kHarmonic = "harmonic";
constexpr const char* kMeshMatching = "mesh-matching";

// The paper's numbers (Li, Liao, Tong, section 4): Table 1 (its patient #1, 48,813 tets), Table 2, and the timings.
constexpr std::array<double, 6> kPaperTable1Harmonic = {47.0, 43.9, 5.3, 2.3, 1.0, 0.5};
constexpr std::array<double, 6> kPaperTable1MeshMatching = {15.7, 37.7, 18.8, 14.1, 8.3, 5.4};
constexpr double kPaperMaxHarmonic = 57, kPaperMaxMeshMatching = 98, kPaperMeanHarmonic = 6.8,
                 kPaperMeanMeshMatching = 18.6;
struct PaperModel {
  int tets;
  double harmonic, mesh_matching;
};
constexpr std::array<PaperModel, 8> kPaperTable2 = {{{48813, 0.678, 0.554},
                                                     {37859, 0.674, 0.539},
                                                     {40106, 0.689, 0.558},
                                                     {45698, 0.672, 0.547},
                                                     {36962, 0.667, 0.536},
                                                     {40207, 0.671, 0.531},
                                                     {37493, 0.682, 0.563},
                                                     {39658, 0.676, 0.548}}};
constexpr double kPaperSecondsHarmonic = 13.527 + 11.437, kPaperSecondsMeshMatching = 360;

const std::array<unsigned char, 3> kHarmonicColor = {31, 119, 180}, kMeshMatchingColor = {255, 127, 14},
                                   kGrey = {150, 150, 150};

double total_seconds(const std::map<std::string, double>& seconds) {
  double total = 0;
  for (const auto& [stage, s] : seconds) total += s;
  return total;
}

struct PatientInput {
  std::string name, path;
  std::string constraints;  // the file the transfer took them from (core/workflow/patient_setup.h), or empty: automatic
};

// The patients to compare: the given paths, else the bundled ones. Names are unique, for the plot files.
std::vector<PatientInput> patient_inputs(const Args& args) {
  std::vector<PatientInput> inputs;
  std::vector<std::string> paths;
  if (args.has("PATIENT")) paths.push_back(args.get("PATIENT"));
  paths.insert(paths.end(), args.rest().begin(), args.rest().end());
  if (paths.empty()) {
    for (const BundledModel& m : bundled_patients()) inputs.push_back({m.name, m.mesh, ""});
    if (inputs.empty())
      throw Error(resource_dir(), "no bundled patient found (resources/patients/*/patient.vtu): give PATIENT files");
  }
  std::set<std::string> names;
  for (const std::string& path : paths) {
    if (!fs::exists(path)) throw Error(path, "no such patient file or folder");
    std::string name = fs::path(path).stem().string();
    if (name == "patient" && fs::path(path).has_parent_path()) name = fs::path(path).parent_path().filename().string();
    inputs.push_back({name, path, ""});
  }
  for (PatientInput& in : inputs) {
    const std::string base = in.name;
    for (int k = 2; !names.insert(in.name).second; ++k) in.name = base + "_" + std::to_string(k);
  }
  return inputs;
}

struct PatientComparison {
  PatientInput input;
  int tets = 0, vertices = 0;
  MethodMetrics harmonic, mesh_matching;
  int inverted_before_repair = 0;
  AngleStatistics gradients_before, gradients_after, standard_gradients_before, standard_gradients_after;
  MeshMatchingResult registration;
  std::map<std::string, std::string> plots;
};

std::vector<double> angle_percent(const AngleStatistics& a) {
  std::vector<double> p(a.histogram.begin(), a.histogram.end());
  for (double& x : p) x *= a.angles > 0 ? 100.0 / static_cast<double>(a.angles) : 0.0;
  return p;
}

std::vector<double> uniform_edges(double lo, double hi, int bins) {
  std::vector<double> edges;
  for (int i = 0; i <= bins; ++i) edges.push_back(lo + (hi - lo) * i / bins);
  return edges;
}

// The three plots of one patient, in `dir`; returns their file names by kind.
std::map<std::string, std::string> write_plots(const fs::path& dir, const PatientComparison& c,
                                               const Eigen::VectorXd& standard_shape) {
  std::map<std::string, std::string> files = {{"dihedral_distortion", c.input.name + "_dihedral_distortion.png"},
                                              {"element_shape", c.input.name + "_element_shape.png"},
                                              {"gradient_angles", c.input.name + "_gradient_angles.png"}};
  HistogramPlot distortion;
  distortion.title = c.input.name + ": change of the dihedral angles against the standard (paper Table 1)";
  distortion.x_label = "absolute change of a cell's dihedral angle (degrees; the last bin holds all above)";
  distortion.edges = uniform_edges(0, 90, 45);
  distortion.series = {
      {"harmonic", kHarmonicColor, percent_histogram(c.harmonic.dihedral_changes, distortion.edges)},
      {"mesh matching", kMeshMatchingColor, percent_histogram(c.mesh_matching.dihedral_changes, distortion.edges)}};
  write_histogram_png((dir / files["dihedral_distortion"]).string(), distortion);

  HistogramPlot shape;
  shape.title = c.input.name + ": element shape (Verdict hex shape, paper Table 2)";
  shape.x_label = "shape of a cell (0: inverted or flat, 1: ideal)";
  shape.edges = uniform_edges(0, 1, 40);
  shape.series = {{"standard", kGrey, percent_histogram(standard_shape, shape.edges)},
                  {"harmonic", kHarmonicColor, percent_histogram(c.harmonic.shape, shape.edges)},
                  {"mesh matching", kMeshMatchingColor, percent_histogram(c.mesh_matching.shape, shape.edges)}};
  write_histogram_png((dir / files["element_shape"]).string(), shape);

  HistogramPlot gradients;
  gradients.title = c.input.name + ": angles between the field gradients, per tet (paper Fig. 6)";
  gradients.x_label = "angle between two of grad u, grad v, grad w (degrees)";
  gradients.edges = uniform_edges(0, 180, static_cast<int>(c.gradients_before.histogram.size()));
  gradients.series = {{"patient, before", {174, 199, 232}, angle_percent(c.gradients_before)},
                      {"patient, after the improvement", kHarmonicColor, angle_percent(c.gradients_after)},
                      {"standard, before", {200, 200, 200}, angle_percent(c.standard_gradients_before)},
                      {"standard, after", {90, 90, 90}, angle_percent(c.standard_gradients_after)}};
  write_histogram_png((dir / files["gradient_angles"]).string(), gradients);
  return files;
}

json patient_json(const PatientComparison& c) {
  json harmonic = to_json(c.harmonic);
  harmonic["inverted_before_repair"] = c.inverted_before_repair;
  harmonic["seconds_without_standard"] =
      c.harmonic.seconds.count("standard_parameterization")
          ? total_seconds(c.harmonic.seconds) - c.harmonic.seconds.at("standard_parameterization")
          : total_seconds(c.harmonic.seconds);
  harmonic["gradient_angles_mean_deviation_from_90_deg"] = {{"before", c.gradients_before.mean_deviation_from_90},
                                                            {"after", c.gradients_after.mean_deviation_from_90}};
  json matching = to_json(c.mesh_matching);
  matching["similarity_scale"] = c.registration.scale;
  matching["control_points"] = c.registration.control_points;
  matching["iterations"] = c.registration.iterations.size();
  return {{"name", c.input.name},
          {"path", c.input.path},
          {"constraints", c.input.constraints.empty() ? "automatic" : c.input.constraints},
          {"tets", c.tets},
          {"vertices", c.vertices},
          {"methods", {{kHarmonic, harmonic}, {kMeshMatching, matching}}},
          {"plots", c.plots}};
}

json paper_json() {
  json table2 = json::array();
  for (size_t i = 0; i < kPaperTable2.size(); ++i)
    table2.push_back({{"model", "#" + std::to_string(i + 1)},
                      {"tets", kPaperTable2[i].tets},
                      {kHarmonic, kPaperTable2[i].harmonic},
                      {kMeshMatching, kPaperTable2[i].mesh_matching}});
  return {
      {"table1",
       {{"bins_from_deg", DihedralDistortion::kBinLower},
        {kHarmonic, {{"percent", kPaperTable1Harmonic}, {"max", kPaperMaxHarmonic}, {"mean", kPaperMeanHarmonic}}},
        {kMeshMatching,
         {{"percent", kPaperTable1MeshMatching}, {"max", kPaperMaxMeshMatching}, {"mean", kPaperMeanMeshMatching}}}}},
      {"table2", table2},
      {"seconds", {{kHarmonic, kPaperSecondsHarmonic}, {kMeshMatching, kPaperSecondsMeshMatching}}}};
}

std::string bin_name(size_t b) {
  const auto& lo = DihedralDistortion::kBinLower;
  return b + 1 < lo.size() ? fmt("%.0f", lo[b]) + "–" + fmt("%.0f", lo[b + 1]) + "°" : "> " + fmt("%.0f", lo[b]) + "°";
}

std::string stages_text(const std::map<std::string, double>& seconds) {
  std::string s;
  for (const auto& [stage, t] : seconds) s += (s.empty() ? "" : ", ") + stage + " " + fmt("%.2f", t);
  return s;
}

std::string report_markdown(const std::string& command, const std::string& standard_name,
                            const QualitySummary& standard_quality, const std::vector<PatientComparison>& patients) {
  std::ostringstream md;
  md << "# Harmonic-field transfer vs mesh matching\n\n"
     << "Regenerate with `" << command << "`. Paper: Li, Liao, Tong, section 4 (Tables 1-2); the baseline is "
     << "described in docs/method.md (mesh-matching baseline).\n\n"
     << "Standard: " << standard_name << ", " << standard_quality.cells << " cells (" << standard_quality.hexes
     << " hexes, " << standard_quality.wedges << " wedges), mean shape " << fmt("%.3f", standard_quality.shape_mean)
     << ", min shape " << fmt("%.3f", standard_quality.shape_min) << ".\n\n";

  md << "## Table 1: dihedral-angle distortion (% of cell edges)\n\n| change | paper: harmonic | paper: mesh matching "
        "|";
  for (const auto& c : patients) md << " " << c.input.name << ": harmonic | " << c.input.name << ": mesh matching |";
  md << "\n|---|---:|---:|";
  for (size_t i = 0; i < patients.size(); ++i) md << "---:|---:|";
  md << "\n";
  for (size_t b = 0; b < kPaperTable1Harmonic.size(); ++b) {
    md << "| " << bin_name(b) << " | " << fmt("%.1f", kPaperTable1Harmonic[b]) << " | "
       << fmt("%.1f", kPaperTable1MeshMatching[b]) << " |";
    for (const auto& c : patients)
      md << " " << fmt("%.1f", c.harmonic.quality.distortion.percent[b]) << " | "
         << fmt("%.1f", c.mesh_matching.quality.distortion.percent[b]) << " |";
    md << "\n";
  }
  md << "| max (°) | " << fmt("%.0f", kPaperMaxHarmonic) << " | " << fmt("%.0f", kPaperMaxMeshMatching) << " |";
  for (const auto& c : patients)
    md << " " << fmt("%.1f", c.harmonic.quality.distortion.max_deg) << " | "
       << fmt("%.1f", c.mesh_matching.quality.distortion.max_deg) << " |";
  md << "\n| mean (°) | " << fmt("%.1f", kPaperMeanHarmonic) << " | " << fmt("%.1f", kPaperMeanMeshMatching) << " |";
  for (const auto& c : patients)
    md << " " << fmt("%.2f", c.harmonic.quality.distortion.mean_deg) << " | "
       << fmt("%.2f", c.mesh_matching.quality.distortion.mean_deg) << " |";

  md << "\n\n## Table 2: mean element shape (Verdict hex shape)\n\n"
     << "| model | tets | harmonic | mesh matching |\n|---|---:|---:|---:|\n";
  for (const auto& c : patients)
    md << "| " << c.input.name << " | " << c.tets << " | " << fmt("%.3f", c.harmonic.quality.summary.shape_mean)
       << " | " << fmt("%.3f", c.mesh_matching.quality.summary.shape_mean) << " |\n";
  for (size_t i = 0; i < kPaperTable2.size(); ++i)
    md << "| paper #" << i + 1 << " | " << kPaperTable2[i].tets << " | " << fmt("%.3f", kPaperTable2[i].harmonic)
       << " | " << fmt("%.3f", kPaperTable2[i].mesh_matching) << " |\n";

  md << "\n## Validity and fit\n\nHarmonic: after the shape relaxation and the repair of inverted cells "
        "(docs/method.md "
        "sections 6c and 7; the plain mapping's count in brackets). Mesh matching: as registered, nothing repaired. "
        "Side vertices: the mapped standard vertices on a "
        "side, distance to the patient's boundary.\n\n"
     << "| patient | method | inverted | degenerate | min scaled Jacobian | % scaled Jacobian < 0.3 | min shape | "
        "side vertices off the surface, mean / p95 / max (mm) |\n|---|---|---:|---:|---:|---:|---:|---|\n";
  for (const auto& c : patients)
    for (const auto* m : {&c.harmonic, &c.mesh_matching}) {
      const QualitySummary& q = m->quality.summary;
      const bool harmonic = m == &c.harmonic;
      md << "| " << c.input.name << " | " << (harmonic ? "harmonic" : "mesh matching") << " | " << q.inverted
         << (harmonic ? " (" + std::to_string(c.inverted_before_repair) + ")" : "") << " | " << q.degenerate << " | "
         << fmt("%.3f", q.scaled_jacobian_min) << " | " << fmt("%.2f", 100 * q.fraction_scaled_jacobian_below_0_3)
         << " | " << fmt("%.3f", q.shape_min) << " | " << fmt("%.3f", m->side_distance.mean) << " / "
         << fmt("%.3f", m->side_distance.p95) << " / " << fmt("%.3f", m->side_distance.max) << " |\n";
    }

  md << "\n## Time (s)\n\nPaper (Core2Quad 2.4 GHz, 48,813 tets): harmonic " << fmt("%.1f", kPaperSecondsHarmonic)
     << " (parameterization 13.5 + mapping 11.4), mesh matching about " << fmt("%.0f", kPaperSecondsMeshMatching)
     << ". The standard's parameterization is needed once per standard (the paper does not count it).\n\n"
     << "| patient | method | total | without the standard | stages |\n|---|---|---:|---:|---|\n";
  for (const auto& c : patients) {
    const double standard_s =
        c.harmonic.seconds.count("standard_parameterization") ? c.harmonic.seconds.at("standard_parameterization") : 0;
    md << "| " << c.input.name << " | harmonic | " << fmt("%.2f", total_seconds(c.harmonic.seconds)) << " | "
       << fmt("%.2f", total_seconds(c.harmonic.seconds) - standard_s) << " | " << stages_text(c.harmonic.seconds)
       << " |\n| " << c.input.name << " | mesh matching | " << fmt("%.2f", total_seconds(c.mesh_matching.seconds))
       << " | " << fmt("%.2f", total_seconds(c.mesh_matching.seconds)) << " | " << stages_text(c.mesh_matching.seconds)
       << " |\n";
  }

  md << "\n## Plots\n";
  for (const auto& c : patients) {
    md << "\n### " << c.input.name << " (" << c.input.path
       << ", constraints: " << (c.input.constraints.empty() ? "automatic" : c.input.constraints) << ")\n\n"
       << "Mean |90° - gradient angle|: " << fmt("%.1f", c.gradients_before.mean_deviation_from_90) << "° before, "
       << fmt("%.1f", c.gradients_after.mean_deviation_from_90) << "° after the orthogonality improvement.\n\n";
    for (const auto& [kind, file] : c.plots) md << "![" << kind << "](" << file << ")\n\n";
  }
  return md.str();
}

}  // namespace

MethodMetrics method_metrics(const VolumeMesh& standard, const VolumeMesh& mapped, const Eigen::MatrixXd& patient_V,
                             const Eigen::MatrixXi& patient_T, const std::map<std::string, double>& seconds) {
  MethodMetrics m;
  m.quality = quality_report(mapped, &standard);
  m.shape = element_quality(mapped).shape;
  m.dihedral_changes = dihedral_angle_changes(standard, mapped);
  m.side_distance = side_vertex_distances(mapped.V, standard, patient_V, patient_T);
  m.seconds = seconds;
  return m;
}

json to_json(const MethodMetrics& m) {
  const QualitySummary& q = m.quality.summary;
  const DihedralDistortion& d = m.quality.distortion;
  return {{"shape_mean", q.shape_mean},
          {"shape_min", q.shape_min},
          {"dihedral_mean", d.mean_deg},
          {"dihedral_max", d.max_deg},
          {"dihedral_bins_percent", d.percent},
          {"inverted", q.inverted},
          {"degenerate", q.degenerate},
          {"scaled_jacobian_min", q.scaled_jacobian_min},
          {"percent_scaled_jacobian_below_0_3", 100 * q.fraction_scaled_jacobian_below_0_3},
          {"side_vertex_distance_mm",
           {{"mean", m.side_distance.mean}, {"p95", m.side_distance.p95}, {"max", m.side_distance.max}}},
          {"seconds", total_seconds(m.seconds)},
          {"stages", m.seconds}};
}

MatchingOutputs execute_mesh_matching(const VolumeMesh& standard, const std::string& standard_source,
                                      const VolumeMesh& patient, const std::string& patient_source) {
  MatchingOutputs out;
  std::cerr << "mesh matching: registering the boundary of " << standard_source << " onto " << patient_source << "\n";
  TerminalProgress progress;
  out.result = mesh_matching(standard, standard_source, patient, patient_source, {}, progress.callback());
  progress.finish();
  out.metrics = method_metrics(standard, out.result.hex, patient.V, patient.tets(), out.result.seconds);
  out.standard_quality = quality_report(standard, nullptr);
  return out;
}

json mesh_matching_report(const MatchingOutputs& out) {
  json iterations = json::array();
  for (const auto& it : out.result.iterations)
    iterations.push_back({{"stage", it.stage},
                          {"stiffness", it.stiffness},
                          {"standard_to_patient_mm", it.standard_to_patient_mm},
                          {"patient_to_standard_mm", it.patient_to_standard_mm}});
  const DistanceSummary& d = out.metrics.side_distance;
  return {{"format", "facehex-report"},
          {"version", 1},
          {"method", kMeshMatching},
          {"seconds", out.result.seconds},
          {"total_seconds", total_seconds(out.result.seconds)},
          {"registration",
           {{"similarity_scale", out.result.scale},
            {"control_points", out.result.control_points},
            {"iterations", iterations}}},
          {"standard", {{"quality", to_json(out.standard_quality)}}},
          {"transfer",
           {{"side_vertex_distance_mm", {{"points", d.points}, {"max", d.max}, {"p95", d.p95}, {"mean", d.mean}}}}},
          {"patient_hex", {{"quality", to_json(out.metrics.quality)}}}};
}

std::string mesh_matching_summary_text(const MatchingOutputs& out) {
  std::ostringstream os;
  const MeshMatchingResult& r = out.result;
  os << "mesh matching: similarity scale " << fmt("%.3f", r.scale) << ", " << r.control_points
     << " spline control points, " << r.iterations.size() << " iterations; last mean closest-point distance "
     << fmt("%.2f", r.iterations.empty() ? 0.0 : r.iterations.back().standard_to_patient_mm)
     << " mm (standard to patient), "
     << fmt("%.2f", r.iterations.empty() ? 0.0 : r.iterations.back().patient_to_standard_mm)
     << " mm (patient to standard)\n"
     << "standard hex mesh:\n"
     << quality_text(out.standard_quality) << "patient hex mesh (nothing repaired):\n"
     << quality_text(out.metrics.quality) << "  side vertices off the patient surface: mean "
     << fmt("%.2g", out.metrics.side_distance.mean) << " mm, p95 " << fmt("%.2g", out.metrics.side_distance.p95)
     << " mm, max " << fmt("%.2g", out.metrics.side_distance.max) << " mm\n"
     << "time: " << fmt("%.2f", total_seconds(r.seconds)) << " s\n";
  return os.str();
}

int cmd_compare(const Argv& argv) {
  Args args(
      "compare",
      "The paper's comparison (section 4): for each patient (default: the bundled ones), the harmonic transfer "
      "and the mesh-matching baseline, measured against the standard. OUT/ gets report.md, report.json and per "
      "patient PNG histograms of the dihedral-angle distortion, the element shape and the gradient angles. A "
      "patient's constraints: NAME.json or constraints.json beside a mesh file if present, else automatic (sides + "
      "landmark features).");
  args.positional("PATIENT", "patient tet models, closed surfaces or CTs (several allowed)", false)
      .last_positional_repeats()
      .option("output", "output folder");
  add_transfer_options(args);
  if (!args.parse(argv)) return 0;
  if (!args.has("output")) throw UsageError("facehex compare", "missing -o OUTPUT_FOLDER");
  const std::vector<PatientInput> inputs = patient_inputs(args);
  OutputFolder folder(args.get("output"));
  const fs::path& out_dir = folder.path();
  std::string command = "facehex compare";
  for (const std::string& a : argv) command += " " + a;

  std::vector<PatientComparison> results;
  std::string standard_name;
  QualitySummary standard_quality;
  json patients = json::array();
  for (size_t i = 0; i < inputs.size(); ++i) {
    const PatientInput& in = inputs[i];
    const std::string step = "[" + std::to_string(i + 1) + "/" + std::to_string(inputs.size()) + "] " + in.name;
    std::cerr << step << ": harmonic transfer\n";
    const CliTransfer t = cli_transfer(args, in.path, "", "a file NAME.json or constraints.json beside the model");
    const TransferResult& h = t.result;
    std::cerr << step << ": mesh matching\n";
    const std::string& standard_source = t.standard.path;
    MatchingOutputs m = execute_mesh_matching(t.standard.mesh, standard_source, t.patient.mesh, in.path);
    std::cerr << step << ": measuring and plotting\n";
    PatientComparison c;
    c.input = in;
    c.input.constraints = t.patient.constraints_path;
    c.tets = static_cast<int>(h.run.patient.T.rows());
    c.vertices = static_cast<int>(h.run.patient.V.rows());
    c.harmonic = method_metrics(t.standard.mesh, h.run.patient_hex, h.run.patient.V, h.run.patient.T, h.run.seconds);
    c.mesh_matching = std::move(m.metrics);
    c.registration = std::move(m.result);
    c.inverted_before_repair = h.plain_mapping_quality.summary.inverted;  // the mapping's, before relaxation and repair
    c.gradients_before = h.run.patient.fields.angles_initial;
    c.gradients_after = h.run.patient.fields.angles;
    c.standard_gradients_before = h.run.standard.fields.angles_initial;
    c.standard_gradients_after = h.run.standard.fields.angles;
    c.plots = write_plots(out_dir, c, element_quality(t.standard.mesh).shape);
    standard_name = standard_source;
    standard_quality = h.standard_quality.summary;
    patients.push_back(patient_json(c));
    results.push_back(std::move(c));
  }
  const json report = {{"format", "facehex-compare"},
                       {"version", 1},
                       {"command", command},
                       {"standard",
                        {{"path", standard_name},
                         {"cells", standard_quality.cells},
                         {"hexes", standard_quality.hexes},
                         {"wedges", standard_quality.wedges},
                         {"shape_mean", standard_quality.shape_mean},
                         {"shape_min", standard_quality.shape_min}}},
                       {"dihedral_bins_from_deg", DihedralDistortion::kBinLower},
                       {"patients", patients},
                       {"paper", paper_json()}};
  write_text_file((out_dir / "report.json").string(), report.dump(2) + "\n");
  write_text_file((out_dir / "report.md").string(), report_markdown(command, standard_name, standard_quality, results));
  folder.keep();
  std::cout << "patient / method                 shape mean  dihedral mean (deg)  inverted  seconds\n";
  for (const auto& c : results)
    for (const auto* m : {&c.harmonic, &c.mesh_matching}) {
      const std::string label = c.input.name + " / " + (m == &c.harmonic ? kHarmonic : kMeshMatching);
      std::cout << label << std::string(label.size() < 33 ? 33 - label.size() : 1, ' ')
                << fmt("%10.3f", m->quality.summary.shape_mean) << fmt("%21.2f", m->quality.distortion.mean_deg)
                << fmt("%10.0f", m->quality.summary.inverted) << fmt("%9.1f", total_seconds(m->seconds)) << "\n";
    }
  std::cout << "wrote " << (out_dir / "report.md").string() << ", report.json and " << 3 * results.size() << " plots\n";
  return 0;
}

}  // namespace facehex::cli
