#pragma once
// facehex compare (paper section 4, Tables 1-2): the harmonic transfer against the mesh-matching baseline
// (core/baseline/mesh_matching.h) on one standard and several patients, with report.md, report.json and PNG plots;
// and the mesh-matching run that `facehex map --method mesh-matching` shares.
#include <Eigen/Core>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "core/baseline/mesh_matching.h"
#include "core/mesh/mesh.h"
#include "core/quality/surface_distance.h"
#include "core/workflow/report.h"

namespace facehex::cli {

// What the comparison reports for one method on one patient.
struct MethodMetrics {
  MeshQualityReport quality;              // Table 2 (shape), validity, and Table 1 (distortion against the standard)
  DistanceSummary side_distance;          // the mapped standard's side vertices to the patient's boundary (mm)
  Eigen::VectorXd shape;                  // #C, per cell (histogram)
  Eigen::VectorXd dihedral_changes;       // per cell edge, degrees (histogram)
  std::map<std::string, double> seconds;  // per stage
};

// standard: the hex mesh; mapped: it on the patient (same connectivity); patient: V #V x 3, T #T x 4.
MethodMetrics method_metrics(const VolumeMesh& standard, const VolumeMesh& mapped, const Eigen::MatrixXd& patient_V,
                             const Eigen::MatrixXi& patient_T, const std::map<std::string, double>& seconds);

// {"shape_mean", "shape_min", "dihedral_mean", "dihedral_max", "dihedral_bins_percent" (the six bins of Table 1),
//  "inverted", "degenerate", "scaled_jacobian_min", "percent_scaled_jacobian_below_0_3",
//  "side_vertex_distance_mm": {"mean", "p95", "max"}, "seconds" (total), "stages": {name: seconds}}
nlohmann::json to_json(const MethodMetrics& m);

struct MatchingOutputs {
  MeshMatchingResult result;
  MethodMetrics metrics;
  MeshQualityReport standard_quality;
};

// The baseline with its default options, progress on stderr.
MatchingOutputs execute_mesh_matching(const VolumeMesh& standard, const std::string& standard_source,
                                      const VolumeMesh& patient, const std::string& patient_source);

// The report of `facehex map --method mesh-matching`, laid out as run_report's where they share keys
// ("seconds", "total_seconds", "transfer"/"side_vertex_distance_mm", "patient_hex"/"quality").
nlohmann::json mesh_matching_report(const MatchingOutputs& out);
std::string mesh_matching_summary_text(const MatchingOutputs& out);

}  // namespace facehex::cli
