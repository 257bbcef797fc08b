// facehex bench: stage timings of one patient transfer at several model sizes (synthetic face-like shells made
// with TetGen), the bundled standard's parameterization computed once beforehand (it is cached in practice).
#include "app/cli_args.h"
#include "app/commands.h"
#include "app/synthetic_patient.h"
#include "core/constraint_set.h"
#include "core/error.h"
#include "core/harmonic_fields.h"
#include "core/hex_transfer.h"
#include "core/io/mesh_io.h"
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
#include <sstream>

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
            "bundled standard's parameterization is computed once first).");
  args.option("sizes", "approximate tet counts", "10000,50000,200000,1000000").flag("json", "print JSON");
  if (!args.parse(argv)) return 0;
  const std::vector<long> sizes = parse_sizes(args.get("sizes"));

  const BundledModel standard_files = default_standard();
  const VolumeMesh standard = read_volume_mesh(standard_files.mesh);
  const StandardDomain domain = closed_domain(standard);
  const ModelParameterization standard_param =
      parameterize_model(domain.V, domain.T, domain.side_mask, read_constraint_set(standard_files.constraints),
                         standard_files.constraints, HarmonicFieldsOptions{});
  const Eigen::MatrixXd standard_uvw = standard_param.fields.uvw.topRows(standard.num_vertices());

  // Calibrate the edge length for a tet count on a small shell: tets scale as edge^-3.
  const double calibration_edge = 6.0;
  const double calibration_tets = synthetic_shell_patient(calibration_edge).num_cells();
  nlohmann::json results = nlohmann::json::array();
  const std::string tmp = (std::filesystem::temp_directory_path() / "facehex-bench.vtu").string();
  for (const long target : sizes) {
    const double edge = calibration_edge * std::cbrt(calibration_tets / static_cast<double>(target));
    std::cerr << "building a synthetic patient of about " << target << " tets (edge " << edge << " mm)\n";
    VolumeMesh patient = synthetic_shell_patient(edge);
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
    results.push_back({{"tets", patient.num_cells()}, {"vertices", patient.num_vertices()}, {"stages", stages},
                       {"total_seconds", total}});
    if (!args.has("json")) {
      std::printf("%9d tets %8d vertices  transfer %.3f s\n", patient.num_cells(), patient.num_vertices(), total);
      for (const auto& [name, s] : stages) std::printf("    %-36s %9.4f s\n", name.c_str(), s);
    }
  }
  std::filesystem::remove(tmp);
  if (args.has("json")) std::cout << results.dump(2) << "\n";
  return 0;
}

}  // namespace facehex::cli
