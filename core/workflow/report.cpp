#include "core/workflow/report.h"

#include <cstdio>
#include <sstream>

#include "core/fields/constraint_set.h"
#include "core/mesh/tet_topology.h"
#include "core/util/error.h"
#include "core/util/text_file.h"
#include "core/workflow/thread_count.h"

namespace facehex {

std::string fmt(const char* format, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, x);
  return buf;
}

namespace {

using nlohmann::json;

json angles_json(const AngleStatistics& a) {
  return {{"mean_deviation_from_90_deg", a.mean_deviation_from_90},
          {"fraction_within_10_deg_of_90", a.fraction_within_10_of_90},
          {"histogram_bin_deg", AngleStatistics::kBinWidth},
          {"histogram", a.histogram}};
}

json health_json(const ParamHealth& h) {
  return {{"tets", h.tets},
          {"orientation", h.orientation},
          {"inverted", h.inverted},
          {"degenerate", h.degenerate},
          {"flat_by_constraint", h.flat_by_constraint},
          {"coordinates_outside_cube", h.outside_cube},
          {"ok", h.ok()},
          {"first_inverted_tets", h.inverted_tets}};
}

json parameterization_json(const ModelParameterization& m) {
  json fixed = json::object();
  for (int f = 0; f < 3; ++f) fixed[kFieldNames[f]] = m.constraints.fields[f].vertices.size();
  return {{"vertices", m.V.rows()},
          {"tets", m.T.rows()},
          {"fixed_vertices", fixed},
          {"health", health_json(m.health)},
          {"gradient_angles_before", angles_json(m.fields.angles_initial)},
          {"gradient_angles_after", angles_json(m.fields.angles)},
          {"seconds", m.fields.seconds}};
}

json untangle_json(const UntangleReport& u) {
  return {{"inverted_before", u.inverted_before},
          {"inverted_after", u.inverted_after},
          {"degenerate_before", u.degenerate_before},
          {"degenerate_after", u.degenerate_after},
          {"bad_before", u.bad_before},
          {"bad_after", u.bad_after},
          {"min_scaled_jacobian_before", u.min_scaled_jacobian_before},
          {"min_scaled_jacobian_after", u.min_scaled_jacobian_after},
          {"free_vertices", u.free_vertices},
          {"released_feature_vertices", u.released_feature_vertices},
          {"released_side_vertices", u.released_side_vertices},
          {"sweeps", u.sweeps},
          {"vertex_steps", u.vertex_steps},
          {"settled", u.settled},
          {"stalled_passes", u.stalled_passes}};
}

// The relaxation's report and how far the relaxation and the repair moved the vertices from where the mapping put
// them (mm).
json relaxation_json(const TransferRun& run) {
  json j = untangle_json(run.relaxation);
  const DistanceSummary moved = summarize_distances(moved_from_mapping(run));
  j["moved_from_mapping_mm"] = {{"mean", moved.mean}, {"p95", moved.p95}, {"max", moved.max}};
  return j;
}

}  // namespace

MeshQualityReport quality_report(const VolumeMesh& mesh, const VolumeMesh* reference) {
  MeshQualityReport q;
  q.summary = summarize(mesh, element_quality(mesh));
  if (reference) {
    q.has_distortion = true;
    q.distortion = dihedral_distortion(*reference, mesh);
  }
  return q;
}

json to_json(const MeshQualityReport& q) {
  const QualitySummary& s = q.summary;
  json j = {{"cells", s.cells},
            {"hexes", s.hexes},
            {"wedges", s.wedges},
            {"inverted", s.inverted},
            {"degenerate", s.degenerate},
            {"shape_min", s.shape_min},
            {"shape_mean", s.shape_mean},
            {"scaled_jacobian_min", s.scaled_jacobian_min},
            {"scaled_jacobian_mean", s.scaled_jacobian_mean},
            {"percent_scaled_jacobian_below_0_3", 100.0 * s.fraction_scaled_jacobian_below_0_3}};
  if (q.has_distortion) {
    json bins = json::array();
    const auto& lo = DihedralDistortion::kBinLower;
    for (size_t b = 0; b < lo.size(); ++b)
      bins.push_back({{"from_deg", lo[b]},
                      {"to_deg", b + 1 < lo.size() ? json(lo[b + 1]) : json(nullptr)},
                      {"percent", q.distortion.percent[b]}});
    j["dihedral_distortion"] = {{"bins", bins},
                                {"max_deg", q.distortion.max_deg},
                                {"mean_deg", q.distortion.mean_deg},
                                {"percent_below_16_deg", q.distortion.percent[0] + q.distortion.percent[1]},
                                {"angles", q.distortion.angles}};
  }
  return j;
}

std::string quality_text(const MeshQualityReport& q) {
  const QualitySummary& s = q.summary;
  std::ostringstream os;
  os << "  cells " << s.cells << " (" << s.hexes << " hex, " << s.wedges << " wedge), inverted " << s.inverted
     << ", degenerate " << s.degenerate << "\n"
     << "  shape           min " << fmt("%.3f", s.shape_min) << "  mean " << fmt("%.3f", s.shape_mean) << "\n"
     << "  scaled Jacobian min " << fmt("%.3f", s.scaled_jacobian_min) << "  mean "
     << fmt("%.3f", s.scaled_jacobian_mean)
     << "  below 0.3: " << fmt("%.2f", 100 * s.fraction_scaled_jacobian_below_0_3) << " %\n";
  if (q.has_distortion) {
    const auto& d = q.distortion;
    const auto& lo = DihedralDistortion::kBinLower;
    os << "  dihedral-angle distortion against the standard (paper Table 1):\n";
    for (size_t b = 0; b < lo.size(); ++b) {
      const std::string range = b + 1 < lo.size() ? fmt("%.0f", lo[b]) + "-" + fmt("%.0f", lo[b + 1]) + " deg"
                                                  : "> " + fmt("%.0f", lo[b]) + " deg";
      os << "    " << range << std::string(12 - std::min<size_t>(12, range.size()), ' ') << fmt("%5.1f", d.percent[b])
         << " %\n";
    }
    os << "    max " << fmt("%.1f", d.max_deg) << " deg, mean " << fmt("%.2f", d.mean_deg) << " deg\n";
  }
  return os.str();
}

DistanceSummary side_vertex_distances(const Eigen::MatrixXd& mapped_V, const VolumeMesh& standard,
                                      const Eigen::MatrixXd& patient_V, const Eigen::MatrixXi& patient_T) {
  const Eigen::VectorXi mask = side_mask_of(standard);
  std::vector<int> rows;
  for (int v = 0; v < mask.size(); ++v)
    if (mask(v) != 0) rows.push_back(v);
  Eigen::MatrixXd points(static_cast<Eigen::Index>(rows.size()), 3);
  for (size_t i = 0; i < rows.size(); ++i) points.row(static_cast<Eigen::Index>(i)) = mapped_V.row(rows[i]);
  const BoundaryFaces boundary = boundary_faces(patient_T);
  return summarize_distances(distances_to_surface(points, patient_V, boundary.F));
}

DistanceSummary side_vertex_distances(const TransferRun& run, const VolumeMesh& standard) {
  return side_vertex_distances(run.patient_hex.V, standard, run.patient.V, run.patient.T);
}

json read_run_report(const std::string& path) {
  json report;
  try {
    report = json::parse(read_text_file(path));
  } catch (const json::parse_error&) {
    throw Error(path, "not a JSON file (a run's report.json is written last, whole)");
  }
  if (!report.is_object() || report.value("format", "") != "facehex-report")
    throw Error(path, "not a FaceHex run report (\"format\" is not \"facehex-report\")");
  const json& version = report["version"];
  if (!version.is_number_integer() || version.get<int>() != kRunReportVersion)
    throw Error(path, "report version " + version.dump() + ", this facehex reads version " +
                          std::to_string(kRunReportVersion) + " (rerun the patient with this facehex)");
  return report;
}

json landmarks_json(const std::optional<FaceLandmarks>& landmarks) {
  if (!landmarks) return nullptr;
  const size_t estimated = landmarks->estimated.size();
  std::vector<std::string> estimated_names;  // as the patient's sides
  for (const std::string& name : landmarks->estimated)
    estimated_names.push_back(patient_side_name(name, landmarks->scan_frame));
  json objects = json::array();
  for (const SkinObject& o : landmarks->skin_objects)
    objects.push_back({{"z_low", o.z_low},
                       {"z_high", o.z_high},
                       {"thickness_low", o.thickness_low},
                       {"thickness_high", o.thickness_high}});
  return {{"source", landmarks->given ? "given" : "found"},
          {"found", landmarks->points.size() - estimated},
          {"estimated", estimated},
          {"estimated_names", estimated_names},
          {"skin_objects", objects},
          {"mid_sagittal_plane",
           {{"x", landmarks->plane.x},
            {"slope", landmarks->plane.slope},
            {"z", landmarks->plane.z},
            {"turn", landmarks->plane.turn},
            {"y", landmarks->plane.y},
            {"pitch", landmarks->plane.pitch},
            {"source", landmarks->plane_source}}}};
}

json segmentation_json(const std::optional<CtSegmentation>& segmentation) {
  if (!segmentation) return nullptr;
  const CtSegmentation& s = *segmentation;
  const FaceCuts& c = s.cuts;
  return {{"skin_threshold", s.thresholds.skin},
          {"bone_threshold", s.thresholds.bone},
          {"noise",
           {{"sigma", s.noise.sigma},
            {"contrast", s.noise.contrast},
            {"blur_mm", s.noise.blur},
            {"sigma_after", s.noise.sigma_after}}},
          {"cuts",
           {{"top_z", c.top_z},
            {"bottom_z", c.bottom_z},
            {"posterior_y", c.posterior_y},
            {"centre_x", c.centre_x},
            {"head_turn_deg", c.turn.degrees},
            {"head_pitch_deg", c.turn.pitch}}},
          {"edge_length_mm", s.edge_length},
          {"edge_length_rule", s.edge_length_rule},
          {"repair", s.repair},
          {"gantry_tilt_deg", s.gantry_tilt_degrees},
          {"summary", segmentation_summary(s)}};
}

json run_report(const TransferRun& run, const MeshQualityReport& standard_quality,
                const MeshQualityReport& plain_mapping_quality, const MeshQualityReport& patient_quality,
                const DistanceSummary& distance) {
  const TransferStatistics& t = run.transfer;
  double total = 0;
  for (const auto& [stage, s] : run.seconds) total += s;
  return {{"format", "facehex-report"},
          {"version", kRunReportVersion},
          {"facehex_version", FACEHEX_VERSION},
          {"threads", thread_counts().openmp},
          {"seconds", run.seconds},
          {"total_seconds", total},
          {"standard",
           {{"parameterization", parameterization_json(run.standard)},
            {"parameterization_source", run.standard_parameterization_source},
            {"domain", run.standard_domain},
            {"domain_tets_non_positive", run.standard_domain_non_positive},
            {"relaxed_corner_vertices", run.standard_relaxed_corner_vertices},
            {"quality", to_json(standard_quality)}}},
          {"patient", {{"parameterization", parameterization_json(run.patient)}, {"domain", run.patient_domain}}},
          {"transfer",
           {{"vertices", t.vertices},
            {"located_inside", t.located_inside},
            {"located_nearest", t.located_nearest},
            {"max_violation", t.max_violation},
            {"snapped_to_boundary", t.snapped_to_boundary},
            {"snap_failures", t.snap_failures},
            {"walk_hits", t.walk_hits},
            {"side_vertex_distance_mm",
             {{"points", distance.points}, {"max", distance.max}, {"p95", distance.p95}, {"mean", distance.mean}}}}},
          {"relaxation", relaxation_json(run)},
          {"untangle", untangle_json(run.untangle)},
          {"plain_mapping", {{"quality", to_json(plain_mapping_quality)}}},
          {"patient_hex", {{"quality", to_json(patient_quality)}}}};
}

std::string run_summary_text(const TransferRun& run, const MeshQualityReport& standard_quality,
                             const MeshQualityReport& plain_mapping_quality, const MeshQualityReport& patient_quality,
                             const DistanceSummary& distance) {
  std::ostringstream os;
  double total = 0;
  for (const auto& [stage, s] : run.seconds) total += s;
  const ParamHealth& h = run.patient.health;
  os << "patient model: " << run.patient.V.rows() << " vertices, " << run.patient.T.rows() << " tets; "
     << "parameterization: " << h.inverted << " inverted, " << (h.degenerate - h.flat_by_constraint)
     << " degenerate tets\n"
     << "gradient angles, mean |90 - angle|: " << fmt("%.1f", run.patient.fields.angles_initial.mean_deviation_from_90)
     << " deg before, " << fmt("%.1f", run.patient.fields.angles.mean_deviation_from_90)
     << " deg after the orthogonality improvement\n"
     << "mapped hex mesh: " << plain_mapping_quality.summary.inverted << " inverted, shape mean "
     << fmt("%.3f", plain_mapping_quality.summary.shape_mean) << ", dihedral change mean "
     << fmt("%.2f", plain_mapping_quality.distortion.mean_deg) << " deg\n";
  if (run.relaxation.sweeps > 0) {
    const DistanceSummary moved = summarize_distances(moved_from_mapping(run));
    os << "shape relaxation: " << run.relaxation.free_vertices << " vertices, " << run.relaxation.sweeps
       << (run.relaxation.settled ? " sweeps (settled)" : " sweeps") << ", inverted cells "
       << run.relaxation.inverted_before << " -> " << run.relaxation.inverted_after
       << "; vertices moved from the mapping by " << fmt("%.2f", moved.mean) << " mm on average (p95 "
       << fmt("%.2f", moved.p95) << ", max " << fmt("%.1f", moved.max) << ")\n";
  }
  os << "repair: " << run.untangle.inverted_before << " inverted, " << run.untangle.degenerate_before << " flat, "
     << run.untangle.bad_before << " below their scaled-Jacobian bound before; after: " << run.untangle.inverted_after
     << " inverted, " << run.untangle.degenerate_after << " flat, " << run.untangle.bad_after
     << (run.untangle.stalled_passes == 1  ? " (1 pass stopped when its folds stopped decreasing)"
         : run.untangle.stalled_passes > 1 ? " (" + std::to_string(run.untangle.stalled_passes) +
                                                 " passes stopped when their folds stopped decreasing)"
                                           : std::string())
     << "\n"
     << "standard hex mesh:\n"
     << quality_text(standard_quality) << "patient hex mesh:\n"
     << quality_text(patient_quality) << "  side vertices off the patient surface: p95 " << fmt("%.2g", distance.p95)
     << " mm, max " << fmt("%.2g", distance.max) << " mm\n"
     << "time: " << fmt("%.2f", total) << " s\n";
  return os.str();
}

}  // namespace facehex
