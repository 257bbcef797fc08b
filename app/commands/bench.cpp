// facehex bench: stage timings of one patient transfer at several model sizes (synthetic face-like shells made
// with TetGen) or for given patient models, the standard's parameterization read from its cache (or computed once
// when the cache is stale); and the whole run on a resampled CT.
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "app/cli_args.h"
#include "app/commands/bench_correspondence.h"
#include "app/commands/commands.h"
#include "app/transfer_options.h"
#include "core/face/automatic_constraints.h"
#include "core/fields/constraint_set.h"
#include "core/fields/harmonic_fields.h"
#include "core/io/mesh_io.h"
#include "core/mapping/hex_transfer.h"
#include "core/mapping/transfer_pipeline.h"
#include "core/mesh/mesh_check.h"
#include "core/segment/ct_volume.h"
#include "core/segment/voxel_grid.h"
#include "core/standard/parameterization_cache.h"
#include "core/tetgen/tetrahedralize.h"
#include "core/util/error.h"
#include "core/util/resources.h"
#include "core/util/stopwatch.h"
#include "core/workflow/patient_setup.h"

namespace facehex::cli {
namespace {

// Comma-separated positive integers of an option, e.g. "10000,50000".
std::vector<long> parse_counts(const std::string& option, const std::string& text) {
  std::vector<long> counts;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    try {
      counts.push_back(std::stol(item));
    } catch (const std::exception&) {
      counts.push_back(0);
    }
    if (counts.back() <= 0) throw UsageError(option, "expects comma-separated positive integers, got '" + text + "'");
  }
  return counts;
}

// The process's peak resident memory so far, in MB (Linux reports kB).
double peak_memory_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

// --ct NX,NY,NZ: the whole `facehex run` (read, segment, parameterize, map, repair) on the bundled CT resampled
// trilinearly to that grid over the same physical box, read back from a temporary .mha as a user's file would be.
int ct_bench(const Args& args) {
  const std::vector<long> dims = parse_counts("--ct", args.get("ct"));
  if (dims.size() != 3 || *std::min_element(dims.begin(), dims.end()) < 2)
    throw UsageError("--ct", "expects three voxel counts of at least 2, e.g. 512,512,300");
  const std::string tmp = (std::filesystem::temp_directory_path() / "facehex-bench-ct.mha").string();
  {
    const CtVolume ct = read_ct_volume(default_ct());
    const GridGeometry& g = ct.intensity.geometry;
    GridGeometry target;
    target.origin = g.origin;
    for (int a = 0; a < 3; ++a) {
      target.dims[a] = static_cast<int>(dims[a]);
      target.spacing(a) = (g.upper(a) - g.lower(a)) / static_cast<double>(dims[a] - 1);
    }
    std::cerr << "resampling the bundled CT to " << dims[0] << " x " << dims[1] << " x " << dims[2] << " voxels ("
              << target.spacing.transpose() << " mm)\n";
    write_ct_volume(tmp, CtVolume{resample(ct.intensity, target), "resampled"});
  }
  Stopwatch clock;
  const CliTransfer out = cli_transfer(args, tmp, "", "(none for a resampled CT: its face must be found)");
  const double total = clock.lap();
  std::filesystem::remove(tmp);
  std::map<std::string, double> stages = out.result.run.seconds;
  double transfer = 0;
  for (const auto& [name, seconds] : stages) transfer += seconds;
  stages["read_and_segment"] = total - transfer;
  const QualitySummary& q = out.result.patient_quality.summary;
  const nlohmann::json result = {{"ct", dims},
                                 {"tets", out.patient.mesh.num_cells()},
                                 {"stages", stages},
                                 {"total_seconds", total},
                                 {"peak_memory_mb", peak_memory_mb()},
                                 {"inverted", q.inverted + q.degenerate}};
  if (args.has("json")) {
    std::cout << result.dump(2) << "\n";
  } else {
    std::printf("CT %ld x %ld x %ld: patient %d tets, whole run %.2f s, peak memory %.0f MB, %d unusable cells\n",
                dims[0], dims[1], dims[2], out.patient.mesh.num_cells(), total, peak_memory_mb(),
                q.inverted + q.degenerate);
    for (const auto& [name, seconds] : stages) std::printf("    %-36s %9.3f s\n", name.c_str(), seconds);
  }
  return 0;
}

// The standard's side of every transfer (paper 3.4: done once): its mesh and the parameters of its vertices.
struct BenchStandard {
  VolumeMesh mesh;
  Eigen::MatrixXd uvw;
  std::map<std::string, double> feature_values;
  HarmonicFieldsOptions fields;  // --iterations, --order: for the patient too
};

BenchStandard bench_standard(const Args& args) {
  const StandardSetup standard = standard_setup(args);
  BenchStandard b;
  b.mesh = standard.mesh;
  b.fields = field_options(args);
  std::optional<ModelParameterization> param =
      cached_parameterization(standard.path, standard.domain, standard.constraints, b.fields);
  if (!param)
    param = parameterize_model(standard.domain.V, standard.domain.T, standard.domain.side_mask, standard.constraints,
                               standard.source(), b.fields);
  b.uvw = param->fields.uvw.topRows(b.mesh.num_vertices());
  b.feature_values = feature_values(standard.constraints);
  return b;
}

// Times the paper's transfer of one patient (its checks, constraints, parameterization, point location and
// interpolation) and a VTU write + read of it, listed apart. set: the patient's constraint set; nullopt: the
// automatic one (sides + features at the landmarks), found inside the "constraints" stage.
nlohmann::json time_transfer(VolumeMesh patient, const std::optional<ConstraintSet>& set, const BenchStandard& standard,
                             const std::string& source) {
  std::map<std::string, double> stages;
  const std::string tmp = (std::filesystem::temp_directory_path() / "facehex-bench.vtu").string();
  Stopwatch clock;
  write_volume_mesh(tmp, patient);
  patient = read_volume_mesh(tmp);
  std::filesystem::remove(tmp);
  stages["io_write_read_vtu"] = clock.lap();
  check_and_orient_tet_mesh(patient, source);
  stages["mesh_check"] = clock.lap();
  const Eigen::VectorXi side_mask = side_mask_of(patient);
  const ConstraintSet used = set ? *set
                                 : automatic_constraints(patient.V, side_mask, landmark_options_for(patient, source),
                                                         standard.feature_values, kFeatureBand, nullptr);
  stages["constraints"] = clock.lap();
  const ModelParameterization p =
      parameterize_model(patient.V, patient.tets(), side_mask, used, source, standard.fields);
  clock.lap();
  for (const auto& [name, s] : p.fields.seconds) stages[name] = s;
  for (size_t i = 0; i < p.fields.iteration_seconds.size(); ++i)
    stages["orthogonality_iteration_" + std::to_string(i + 1)] = p.fields.iteration_seconds[i];
  stages.erase("orthogonality_improvement");
  TransferStatistics t;
  const PatientMap patient_map(patient.V, p.T, p.fields.uvw);
  stages["locator_build"] = clock.lap();
  transfer_hex_mesh(standard.mesh, standard.uvw, patient_map, &t);
  stages["point_location_and_interpolation"] = t.seconds_mapping;
  double total = 0;
  for (const auto& [name, s] : stages)
    if (name != "io_write_read_vtu") total += s;
  return {{"tets", patient.num_cells()},
          {"vertices", patient.num_vertices()},
          {"stages", stages},
          {"total_seconds", total},
          {"peak_memory_mb", peak_memory_mb()}};  // with sizes ascending, that of the largest run
}

void print_timing(const nlohmann::json& result) {
  std::printf("%9d tets %8d vertices  transfer %.3f s  peak memory %.0f MB\n", result["tets"].get<int>(),
              result["vertices"].get<int>(), result["total_seconds"].get<double>(),
              result["peak_memory_mb"].get<double>());
  for (const auto& [name, s] : result["stages"].items())
    std::printf("    %-36s %9.4f s\n", name.c_str(), s.get<double>());
}

// A synthetic shell patient of about `target` tets (core/synthetic_shell.h, tetrahedralized by TetGen).
VolumeMesh synthetic_patient_of_size(long target, double edge_a, double tets_a, double edge_b, double tets_b) {
  // tets ~ a * edge^-k, with k fitted on two small shells (less than 3: the shell's thickness takes fewer layers of
  // coarse tets than of fine ones).
  const double exponent = std::log(tets_b / tets_a) / std::log(edge_a / edge_b);
  const double edge = edge_b * std::pow(tets_b / static_cast<double>(target), 1.0 / exponent);
  std::cerr << "building a synthetic patient of about " << target << " tets (edge " << edge << " mm)\n";
  VolumeMesh patient = synthetic_shell_patient(edge);
  // The fit is local, and the count jumps where the shell's thickness takes one more layer of tets: bisect the
  // edge (in log scale, between one too fine and one too coarse) for up to three more meshes, keeping the closest.
  auto miss = [&](const VolumeMesh& m) { return std::abs(std::log(m.num_cells() / static_cast<double>(target))); };
  double too_fine = 0, too_coarse = 0;  // edges known to give too many / too few tets (0: none yet)
  double tried = edge;
  int tried_cells = patient.num_cells();
  for (int attempt = 0; attempt < 3 && miss(patient) > std::log(1.25); ++attempt) {
    (tried_cells > target ? too_fine : too_coarse) = tried;
    tried = too_fine > 0 && too_coarse > 0 ? std::sqrt(too_fine * too_coarse)
                                           : tried * std::cbrt(tried_cells / static_cast<double>(target));
    std::cerr << "  got " << tried_cells << " tets; again with edge " << tried << " mm\n";
    VolumeMesh again = synthetic_shell_patient(tried);
    tried_cells = again.num_cells();
    if (miss(again) < miss(patient)) patient = std::move(again);
  }
  return patient;
}

}  // namespace

int cmd_bench(const Argv& argv) {
  Args args("bench",
            "Times each stage of one patient transfer (the paper's scope: checks, constraints, parameterization, "
            "point location and interpolation) for synthetic patients of about the given tet counts, or for given "
            "patient models. The standard's parameterization is read from its cache first.");
  args.option("sizes", "approximate tet counts", "10000,50000,200000,1000000")
      .option("patient",
              "instead: time these patients, as run takes them (tet models, closed surfaces or CTs, segmented first "
              "and not timed; comma-separated; constraints: NAME.json or constraints.json beside a mesh file, else "
              "automatic)")
      .option("ct", "instead: time the whole run on the bundled CT resampled to NX,NY,NZ voxels (e.g. 512,512,300)")
      .flag("json", "print JSON");
  add_correspondence_options(args);
  add_transfer_options(args);
  if (!args.parse(argv)) return 0;
  if (args.has("correspondence")) return correspondence_bench(args);
  if (args.has("ct")) return ct_bench(args);
  std::vector<std::string> patients;
  if (args.has("patient")) {
    std::stringstream ss(args.get("patient"));
    for (std::string item; std::getline(ss, item, ',');) {
      if (!std::filesystem::exists(item)) throw Error(item, "no such patient file or DICOM folder");
      patients.push_back(item);
    }
  }
  const std::vector<long> sizes = patients.empty() ? parse_counts("--sizes", args.get("sizes")) : std::vector<long>{};
  const long most = static_cast<long>(max_tets_for_memory());
  for (const long n : sizes)
    if (n > most)
      throw UsageError("--sizes", "expects tet counts up to " + std::to_string(most) +
                                      ", what this machine's memory carries through a transfer; got " +
                                      std::to_string(n));

  const BenchStandard standard = bench_standard(args);
  nlohmann::json results = nlohmann::json::array();
  for (const std::string& file : patients) {
    // A constraint file as run finds one; else the automatic constraints, placed inside the timed stages.
    const PatientSetup patient = load_patient(file, segment_options(args), "", nullptr);
    std::optional<ConstraintSet> set;
    if (!patient.constraints_path.empty()) set = patient.constraints;
    results.push_back(time_transfer(patient.mesh, set, standard, patient.source()));
    results.back()["patient"] = file;
    if (!args.has("json")) print_timing(results.back());
  }
  if (!sizes.empty()) {
    const double edge_a = 6.0, edge_b = 4.0;
    const double tets_a = synthetic_shell_patient(edge_a).num_cells(),
                 tets_b = synthetic_shell_patient(edge_b).num_cells();
    for (const long target : sizes) {
      results.push_back(time_transfer(synthetic_patient_of_size(target, edge_a, tets_a, edge_b, tets_b),
                                      side_constraints(), standard, "synthetic patient"));
      if (!args.has("json")) print_timing(results.back());
    }
  }
  if (args.has("json")) std::cout << results.dump(2) << "\n";
  return 0;
}

}  // namespace facehex::cli
