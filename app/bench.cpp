// facehex bench: stage timings of one patient transfer at several model sizes (synthetic face-like shells made
// with TetGen), the bundled standard's parameterization read from its cache (or computed once when the cache is stale).
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
#include "core/standard/closed_domain.h"
#include "core/stopwatch.h"
#include "core/transfer_pipeline.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <sys/resource.h>

namespace facehex::cli {
namespace {

std::vector<long> parse_sizes(const std::string& text) {
  std::vector<long> sizes;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    try {
      sizes.push_back(std::stol(item));
    } catch (const std::exception&) {
      throw Error("--sizes", "expects comma-separated tet counts, got '" + text + "'");
    }
  }
  return sizes;
}

}  // namespace

int cmd_bench(const Argv& argv) {
  Args args("bench",
            "Times each stage of one patient transfer for synthetic patients of about the given tet counts (the "
            "bundled standard's parameterization is read from its cache first).");
  args.option("sizes", "approximate tet counts", "10000,50000,200000,1000000").flag("json", "print JSON");
  if (!args.parse(argv)) return 0;
  const std::vector<long> sizes = parse_sizes(args.get("sizes"));

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
  const double tets_a = synthetic_shell_patient(edge_a).num_cells(), tets_b = synthetic_shell_patient(edge_b).num_cells();
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
    const ResolvedConstraints constraints = resolve_constraints(side_constraints(), patient.V, patient.tets(),
                                                                side_mask_of(patient), "synthetic patient");
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
    // The process's peak resident memory so far (Linux reports kB): with sizes ascending, that of the largest run.
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    const double peak_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;
    results.push_back({{"tets", patient.num_cells()}, {"vertices", patient.num_vertices()}, {"stages", stages},
                       {"total_seconds", total}, {"peak_memory_mb", peak_mb}});
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
