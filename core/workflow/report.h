#pragma once
// The run report: stage timings, sizes, parameterization health, transfer statistics and the quality tables of
// the paper (Table 1: dihedral-angle distortion; Table 2: mean element shape), as JSON for scripts and as a short
// text summary for people.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/face/face_landmarks.h"
#include "core/mapping/transfer_pipeline.h"
#include "core/mesh/mesh.h"
#include "core/quality/hex_quality.h"
#include "core/quality/surface_distance.h"
#include "core/segment/patient_input.h"

namespace facehex {

// printf-style formatting of one number, for reports.
std::string fmt(const char* format, double x);

struct MeshQualityReport {
  QualitySummary summary;
  bool has_distortion = false;
  DihedralDistortion distortion;
};

MeshQualityReport quality_report(const VolumeMesh& mesh, const VolumeMesh* reference);
nlohmann::json to_json(const MeshQualityReport& q);
std::string quality_text(const MeshQualityReport& q);

// Distances (mm) from the mapped standard vertices that lie on a side (side_mask != 0) to the patient's boundary.
// mapped_V: #Vs x 3, the standard's vertices on the patient; patient: V #V x 3, T #T x 4.
DistanceSummary side_vertex_distances(const Eigen::MatrixXd& mapped_V, const VolumeMesh& standard,
                                      const Eigen::MatrixXd& patient_V, const Eigen::MatrixXi& patient_T);
DistanceSummary side_vertex_distances(const TransferRun& run, const VolumeMesh& standard);

// The schema of report.json, {"format": "facehex-report", "version": kRunReportVersion, ...}: a reader (the cohort
// report, scripts) checks both. Any change of the keys or of what a value means raises it, so that a reader of one
// version finds every key it documents (docs/cohorts.md).
constexpr int kRunReportVersion = 5;

// report.json as written by `facehex run` (or `map`): throws facehex::Error(path, ...) when the file cannot be read
// or parsed, or is not a facehex-report of version kRunReportVersion.
nlohmann::json read_run_report(const std::string& path);

// The landmarks the feature constraints were placed at: {"source": "found" or "given", "found": n, "estimated": n,
// "estimated_names": [...]}; null when there are none (a constraint file was given).
nlohmann::json landmarks_json(const std::optional<FaceLandmarks>& landmarks);

// How a CT was segmented, so that the run can be repeated: {"skin_threshold",
// "bone_threshold" (file units), "noise": {"sigma", "contrast" (file units), "blur_mm", "sigma_after"} (ct_noise.h;
// sigma 0 when not measured), "cuts": {"top_z", "bottom_z", "posterior_y", "centre_x" (mm, head frame),
// "head_turn_deg", "head_pitch_deg"}, "edge_length_mm", "edge_length_rule", "repair", "gantry_tilt_deg", "summary"
// (segmentation_summary's line)}; null for a patient given as a mesh file.
nlohmann::json segmentation_json(const std::optional<CtSegmentation>& segmentation);

// plain_mapping_quality: of run.mapped_hex (the mapping before relaxation and repair) against the standard.
nlohmann::json run_report(const TransferRun& run, const MeshQualityReport& standard_quality,
                          const MeshQualityReport& plain_mapping_quality, const MeshQualityReport& patient_quality,
                          const DistanceSummary& distance);
std::string run_summary_text(const TransferRun& run, const MeshQualityReport& standard_quality,
                             const MeshQualityReport& plain_mapping_quality, const MeshQualityReport& patient_quality,
                             const DistanceSummary& distance);

}  // namespace facehex
