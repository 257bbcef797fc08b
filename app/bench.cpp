// facehex bench: stage timings of one patient transfer at several model sizes (synthetic face-like shells made
// with TetGen), the bundled standard's parameterization read from its cache (or computed once when the cache is stale).
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
#include "app/commands.h"
#include "app/synthetic_patient.h"
#include "app/transfer_command.h"
#include "core/constraint_set.h"
#include "core/error.h"
#include "core/harmonic_fields.h"
#include "core/hex_transfer.h"
#include "core/io/mesh_io.h"
#include "core/io/parameterization_cache.h"
#include "core/mesh_check.h"
#include "core/resources.h"
#include "core/segment/ct_volume.h"
#include "core/segment/voxel_grid.h"
#include "core/standard/closed_domain.h"
#include "core/stopwatch.h"
#include "core/transfer_pipeline.h"

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
    if (counts.back() <= 0) throw Error(option, "expects comma-separated positive integers, got '" + text + "'");
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
    throw Error("--ct", "expects three voxel counts of at least 2, e.g. 512,512,300");
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
  TransferOutputs out = execute_transfer(args, tmp, "");
  const double total = clock.lap();
  std::filesystem::remove(tmp);
  std::map<std::string, double> stages = out.run.seconds;
  double transfer = 0;
  for (const auto& [name, seconds] : stages) transfer += seconds;
  stages["read_and_segment"] = total - transfer;
  const QualitySummary& q = out.patient_quality.summary;
  const nlohmann::json result = {{"ct", dims},
                                 {"tets", out.patient.num_cells()},
                                 {"stages", stages},
                                 {"total_seconds", total},
                                 {"peak_memory_mb", peak_memory_mb()},
                                 {"inverted", q.inverted + q.degenerate}};
  if (args.has("json")) {
    std::cout << result.dump(2) << "\n";
  } else {
    std::printf("CT %ld x %ld x %ld: patient %d tets, whole run %.2f s, peak memory %.0f MB, %d unusable cells\n",
                dims[0], dims[1], dims[2], out.patient.num_cells(), total, peak_memory_mb(), q.inverted + q.degenerate);
    for (const auto& [name, seconds] : stages) std::printf("    %-36s %9.3f s\n", name.c_str(), seconds);
  }
  return 0;
}

}  // namespace

int cmd_bench(const Argv& argv) {
  Args args("bench",
            "Times each stage of one patient transfer for synthetic patients of about the given tet counts (the "
            "bundled standard's parameterization is read from its cache first).");
  args.option("sizes", "approximate tet counts", "10000,50000,200000,1000000")
      .option("ct", "instead: time the whole run on the bundled CT resampled to NX,NY,NZ voxels (e.g. 512,512,300)")
      .flag("json", "print JSON");
  add_transfer_options(args);
  if (!args.parse(argv)) return 0;
  if (args.has("ct")) return ct_bench(args);
  const std::vector<long> sizes = parse_counts("--sizes", args.get("sizes"));

  const BundledModel standard_files = default_standard();
  const VolumeMesh standard = read_volume_mesh(standard_files.mesh);
  const StandardDomain domain = closed_domain(standard);
  const ConstraintSet standard_set = read_constraint_set(standard_files.constraints);
  const std::optional<ModelParameterization> cached = cached_standard_parameterization(
      parameterization_cache_path(standard_files.mesh), domain, standard_set, HarmonicFieldsOptions{});
  const ModelParameterization standard_param =
      cached ? *cached
             : parameterize_model(domain.V, domain.T, domain.side_mask, standard_set, standard_files.constraints,
                                  HarmonicFieldsOptions{});
  const Eigen::MatrixXd standard_uvw = standard_param.fields.uvw.topRows(standard.num_vertices());

  // Calibrate the edge length for a tet count on two small shells: tets ~ a * edge^-k, with k fitted (less than 3:
  // the shell's thickness takes fewer layers of coarse tets than of fine ones).
  const double edge_a = 6.0, edge_b = 4.0;
  const double tets_a = synthetic_shell_patient(edge_a).num_cells(),
               tets_b = synthetic_shell_patient(edge_b).num_cells();
  const double exponent = std::log(tets_b / tets_a) / std::log(edge_a / edge_b);
  nlohmann::json results = nlohmann::json::array();
  const std::string tmp = (std::filesystem::temp_directory_path() / "facehex-bench.vtu").string();
  for (const long target : sizes) {
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
    std::map<std::string, double> stages;
    Stopwatch clock;
    write_volume_mesh(tmp, patient);
    patient = read_volume_mesh(tmp);
    stages["io_write_read_vtu"] = clock.lap();
    check_and_orient_tet_mesh(patient, "synthetic patient");
    stages["mesh_check"] = clock.lap();
    const ResolvedConstraints constraints =
        resolve_constraints(side_constraints(), patient.V, patient.tets(), side_mask_of(patient), "synthetic patient");
    stages["constraints"] = clock.lap();
    const HarmonicFields fields(patient.V, patient.tets(), constraints, HarmonicFieldsOptions{});
    const HarmonicFieldsResult r = fields.compute();
    clock.lap();
    for (const auto& [name, s] : r.seconds) stages[name] = s;
    for (size_t i = 0; i < r.iteration_seconds.size(); ++i)
      stages["orthogonality_iteration_" + std::to_string(i + 1)] = r.iteration_seconds[i];
    stages.erase("orthogonality_improvement");
    TransferStatistics t;
    const Eigen::MatrixXd uvw = r.uvw.cwiseMax(0.0).cwiseMin(1.0);
    const Eigen::MatrixXi T = patient.tets();
    const PatientMap patient_map(patient.V, T, uvw);
    stages["locator_build"] = clock.lap();
    transfer_hex_mesh(standard, standard_uvw, patient_map, &t);
    stages["point_location_and_interpolation"] = t.seconds_mapping;
    double total = 0;
    for (const auto& [name, s] : stages)
      if (name != "io_write_read_vtu") total += s;
    const double peak_mb = peak_memory_mb();  // with sizes ascending, that of the largest run
    results.push_back({{"tets", patient.num_cells()},
                       {"vertices", patient.num_vertices()},
                       {"stages", stages},
                       {"total_seconds", total},
                       {"peak_memory_mb", peak_mb}});
    if (!args.has("json")) {
      std::printf("%9d tets %8d vertices  transfer %.3f s  peak memory %.0f MB\n", patient.num_cells(),
                  patient.num_vertices(), total, peak_mb);
      for (const auto& [name, s] : stages) std::printf("    %-36s %9.4f s\n", name.c_str(), s);
    }
  }
  std::filesystem::remove(tmp);
  if (args.has("json")) std::cout << results.dump(2) << "\n";
  return 0;
}

}  // namespace facehex::cli
