#include "core/workflow/transfer.h"

#include <algorithm>

#include "core/correspondence/side_correspondence.h"
#include "core/face/automatic_constraints.h"
#include "core/io/fe_sets.h"
#include "core/io/mesh_io.h"
#include "core/mesh/sides.h"
#include "core/quality/hex_quality.h"
#include "core/quality/surface_distance.h"
#include "core/standard/closed_domain.h"
#include "core/standard/parameterization_cache.h"
#include "core/standard/standard_features.h"
#include "core/util/stopwatch.h"

namespace facehex {
namespace {

// The fields of a parameterization at the mesh's vertices (the first rows of the parameterized domain).
void attach_fields(VolumeMesh& mesh, const ModelParameterization& p) {
  const Eigen::Index n = mesh.num_vertices();
  const Eigen::MatrixXd uvw = p.fields.uvw.topRows(n);
  mesh.point_data["u"] = uvw.col(0);
  mesh.point_data["v"] = uvw.col(1);
  mesh.point_data["w"] = uvw.col(2);
  mesh.point_data["uvw"] = uvw;
  mesh.point_data["uvw_initial"] = p.fields.uvw_initial.topRows(n);
  mesh.point_data["fixed_uvw"] = p.fixed.topRows(n).cast<double>();
}

// The patient's set without the feature constraints the constraint policy placed (by their names), which are listed in
// `left_out`; a set from a file is the user's and is kept whole.
ConstraintSet without_automatic_features(const PatientSetup& patient, std::vector<std::string>& left_out) {
  if (!patient.constraints_path.empty()) return patient.constraints;
  ConstraintSet kept;
  for (const Constraint& c : patient.constraints.constraints) {
    bool feature = false;
    for (const FeatureSpec& spec : feature_specs()) feature = feature || c.name == spec.name;
    if (feature)
      left_out.push_back(c.name);
    else
      kept.constraints.push_back(c);
  }
  return kept;
}

constexpr double kSlitDepth = 10;  // mm: how far in front of or behind a landmark the skin is looked for

// Landmark pairs that pull the skin registration, and the standard's vertices among them.
struct LandmarkPull {
  PointPairs pairs;
  std::vector<int> standard_vertices;  // the paired landmark vertices
  std::vector<std::string> names;      // the landmarks paired
};

// The patient's landmarks (found, estimated or given) paired with the standard's of the same names
// (standard_features.h) when the user gave them or with options.pull_found_landmarks, but for
// options.landmarks_not_pulled; none otherwise. The standard's side is its landmark
// vertex, the point feature_landing measures (its open eyes' and mouth's corners are its rims' ends), else where its
// finder placed the landmark. The patient's side is the landmark's point on the model's skin: a corner of a closed eye
// or mouth read in the CT lies in a slit the model's skin bridges, and the registration snaps the standard onto these
// points (PointPairs), which must lie on the surface it is registered to. That point is the skin in front of the
// landmark or behind it (along the face's anterior axis, +y: where the landmark is seen from the front, as the
// landing is measured), else its closest point.
LandmarkPull landmark_pull(const StandardSetup& standard, const PatientSetup& patient, const StandardFeatures& features,
                           const TransferOptions& options) {
  LandmarkPull pull;
  if (!patient.landmarks || (!patient.landmarks->given && !options.pull_found_landmarks)) return pull;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> matched;
  for (const NamedLandmark& l : named_landmarks(*patient.landmarks)) {
    const std::vector<std::string>& left_out = options.landmarks_not_pulled;
    const std::string patient_name = patient_side_name(l.name, patient.landmarks->scan_frame);  // as the user names it
    if (std::find(left_out.begin(), left_out.end(), patient_name) != left_out.end()) continue;
    const auto vertex = features.landmark_vertices.find(l.name);
    const auto point = features.landmarks.points.find(l.name);
    if (vertex != features.landmark_vertices.end()) {
      matched.emplace_back(standard.mesh.V.row(vertex->second).transpose(), l.position);
      pull.standard_vertices.push_back(vertex->second);
    } else if (point != features.landmarks.points.end()) {
      matched.emplace_back(point->second, l.position);
    } else {
      continue;
    }
    pull.names.push_back(l.name);
  }
  if (matched.empty()) return pull;
  pull.pairs.standard.resize(static_cast<Eigen::Index>(matched.size()), 3);
  Eigen::MatrixXd at(static_cast<Eigen::Index>(matched.size()), 3);
  for (size_t i = 0; i < matched.size(); ++i) {
    pull.pairs.standard.row(static_cast<Eigen::Index>(i)) = matched[i].first.transpose();
    at.row(static_cast<Eigen::Index>(i)) = matched[i].second.transpose();
  }
  const Eigen::MatrixXi skin = side_triangles(patient.mesh.tets(), side_mask_of(patient.mesh), W1);
  pull.pairs.patient = at;
  if (skin.rows() == 0) return pull;
  const SurfaceLocator locator(patient.mesh.V, skin);
  const SurfaceLocator::Hits ahead = locator.along(at, Eigen::Vector3d::UnitY(), kSlitDepth);
  const SurfaceLocator::Hits closest = locator.closest(at);
  for (Eigen::Index i = 0; i < at.rows(); ++i)
    pull.pairs.patient.row(i) = ahead.face(i) >= 0 ? ahead.point.row(i) : closest.point.row(i);
  return pull;
}

// The standard's vertices the shape relaxation and the repair keep at their registered (u, v): the landmark vertices
// that pulled the registration, which the relaxation would otherwise slide along the skin (by several millimetres)
// off the patient's landmarks, and with hold_registered_skin every skin vertex the registration matched.
std::vector<char> held_vertices(const RegisteredSides& registration, const LandmarkPull& pull,
                                const TransferOptions& options) {
  std::vector<char> held = options.hold_registered_skin ? registration.standard_matched
                                                        : std::vector<char>(registration.standard_matched.size(), 0);
  for (int v : pull.standard_vertices)
    if (v < static_cast<int>(held.size())) held[static_cast<size_t>(v)] = 1;
  return held;
}

// The patient with its model's openings closed (close_openings on its domain, the model's own tets), and what was
// closed in `note`; empty when the model has no opening.
std::optional<PatientSetup> with_openings_closed(const PatientSetup& patient, std::string& note) {
  TetDomain domain = close_openings(patient.domain, "the model's own tets");
  if (domain.closed_openings == 0) return std::nullopt;
  PatientSetup closed = patient;
  closed.mesh = VolumeMesh::from_tets(domain.V, domain.T);
  closed.mesh.point_data[kSideMaskArray] = domain.side_mask.cast<double>();
  closed.mesh.field_data = patient.mesh.field_data;
  note = domain.description.substr(domain.description.find(" with ") + 6);
  closed.domain = std::move(domain);
  return closed;
}

}  // namespace

TransferResult transfer(const StandardSetup& standard, const PatientSetup& patient_as_given,
                        const TransferOptions& options, const ProgressCallback& progress) {
  TransferResult r;
  std::optional<PatientSetup> closed;
  if (standard.domain.closed_openings > 0) closed = with_openings_closed(patient_as_given, r.patient_openings);
  const PatientSetup& patient = closed ? *closed : patient_as_given;
  // A standard whose own landmarks are not found has no features to pull or to follow: its transfer stands.
  std::optional<StandardFeatures> features;
  try {
    features = standard_features(standard.mesh);
  } catch (const Error&) {
  }
  std::optional<ModelParameterization> standard_p =
      cached_parameterization(standard.path, standard.domain, standard.constraints, options.fields, &r.cache_note);
  const bool cached = standard_p.has_value();
  double standard_seconds = 0;
  bool done = false;
  std::vector<std::string> pulled;  // the landmarks that pulled the registration the transfer used
  if (options.skin_correspondence == SkinCorrespondence::registered) {
    if (!standard_p) {
      Stopwatch clock;
      standard_p =
          parameterize_model(standard.domain.V, standard.domain.T, standard.domain.side_mask, standard.constraints,
                             standard.source(), options.fields, sub_progress(progress, 0.0, 0.1));
      standard_seconds = clock.lap();
    }
    try {
      const LandmarkPull pull = features ? landmark_pull(standard, patient, *features, options) : LandmarkPull{};
      const RegisteredSidesOptions registration_options;
      r.registration = register_sides(standard.domain, standard_p->fields.uvw, patient.mesh, patient.source(),
                                      registration_options, &pull.pairs, sub_progress(progress, 0.1, 0.2));
      const SideConditions sides{r.registration->conditions, held_vertices(*r.registration, pull, options)};
      // Only a healthy registered parameterization is taken, whatever allow_inverted_parameterization says: that
      // option is for the map the user cannot do without, and the feature lines remain.
      TransferOptions healthy = options;
      healthy.allow_inverted_parameterization = false;
      r.run = run_transfer(standard.mesh, standard.domain, standard.constraints, standard.source(), patient.mesh,
                           without_automatic_features(patient, r.left_out_constraints), patient.source(), healthy,
                           sub_progress(progress, 0.2, 0.97), &*standard_p, &sides);
      done = true;
      pulled = pull.names;
    } catch (const Error& e) {
      // Where the registered skin cannot give a usable map (the registration left the skins apart and the fields
      // fold), the feature lines still may: the run goes on with them and says why.
      if (!patient.features_problem.empty() && patient.constraints_path.empty())
        throw Error(patient.source(), std::string("the registered skin gave no usable map (") + e.what() +
                                          ") and the facial feature lines cannot be placed (" +
                                          patient.features_problem + "): give the landmarks with --landmarks FILE");
      r.registration.reset();
      r.left_out_constraints.clear();
      r.registered_failure = e.what();
    }
  }
  if (!done) {
    try {
      r.run = run_transfer(standard.mesh, standard.domain, standard.constraints, standard.source(), patient.mesh,
                           patient.constraints, patient.source(), options, sub_progress(progress, 0.2, 0.97),
                           standard_p ? &*standard_p : nullptr);
    } catch (const Error& e) {
      if (r.registered_failure.empty()) throw;
      // Both ways failed: the user needs both reasons, the registered skin's first (it is the default).
      throw Error(e.subject(), "the registered skin gave no usable map (" + r.registered_failure +
                                   "), nor did the feature lines: " + e.problem());
    }
  }
  r.run.patient_domain = patient.domain.description;
  if (cached) r.run.standard_parameterization_source = parameterization_cache_path(standard.path);
  if (!cached && standard_p) {  // computed above for the registration
    r.run.standard_parameterization_source = "computed";
    r.run.seconds["standard_parameterization"] = standard_seconds;
  }
  if (r.registration) r.run.seconds["registration"] = r.registration->seconds;
  report_progress(progress, "quality", 0.97);
  r.patient_hex = decorate_patient_hex(r.run, standard.mesh);
  r.standard_quality = quality_report(standard.mesh, nullptr);
  r.plain_mapping_quality = quality_report(r.run.mapped_hex, &standard.mesh);
  r.patient_quality = quality_report(r.run.patient_hex, &standard.mesh);
  r.distance = side_vertex_distances(r.run, standard.mesh);
  if (patient_as_given.landmarks && features)
    r.landing = feature_landing(*features, r.patient_hex.V, *patient_as_given.landmarks, pulled);
  report_progress(progress, "quality", 1.0);
  return r;
}

nlohmann::json skin_correspondence_json(const TransferResult& result) {
  if (!result.registration) return {{"mode", "features"}, {"registered_failure", result.registered_failure}};
  const RegisteredSides& g = *result.registration;
  const DistanceSummary& d = g.distance;
  return {{"mode", "registered"},
          {"vertices", g.conditions[0].vertices.size()},
          {"too_far", g.vertices_too_far},
          {"pinned_landmarks", g.pinned_landmarks},
          {"distance_mm", {{"mean", d.mean}, {"p95", d.p95}, {"max", d.max}}},
          {"left_out_constraints", result.left_out_constraints},
          {"seconds", g.seconds}};
}

std::string skin_correspondence_text(const TransferResult& result) {
  if (!result.registration)
    return result.registered_failure.empty()
               ? "skin correspondence: the feature constraints (the paper's)\n"
               : "skin correspondence: the feature constraints (the paper's), since the registered skin gave no usable "
                 "map (" +
                     result.registered_failure + ")\n";
  const RegisteredSides& g = *result.registration;
  return "skin correspondence: registered; " + std::to_string(g.conditions[0].vertices.size()) +
         " skin vertices take the standard's (u, v), " + std::to_string(g.vertices_too_far) +
         " left free (farther from the registered standard than the bound); skin from the registered standard: mean " +
         fmt("%.2f", g.distance.mean) + " mm, p95 " + fmt("%.2f", g.distance.p95) + " mm, max " +
         fmt("%.1f", g.distance.max) + " mm\n";
}

VolumeMesh with_quality(VolumeMesh mesh) {
  const ElementQuality q = element_quality(mesh);
  mesh.cell_data["shape"] = q.shape;
  mesh.cell_data["scaled_jacobian"] = q.scaled_jacobian;
  return mesh;
}

VolumeMesh decorate_patient_hex(const TransferRun& run, const VolumeMesh& standard) {
  VolumeMesh hex = with_quality(run.patient_hex);
  hex.point_data["moved_from_mapping"] = moved_from_mapping(run);
  hex.cell_data["dihedral_change"] = cell_dihedral_change(standard, hex);
  hex.point_data["uvw"] = hex_vertex_uvw(run, standard.num_vertices());
  const auto mask = standard.point_data.find(kSideMaskArray);
  if (mask != standard.point_data.end()) hex.point_data[kSideMaskArray] = mask->second;
  attach_fe_arrays(hex);
  return hex;
}

VolumeMesh standard_with_fields(const VolumeMesh& standard, const ModelParameterization& p) {
  VolumeMesh m = with_quality(standard);
  attach_fields(m, p);
  return m;
}

VolumeMesh parameterized_tet_mesh(const ModelParameterization& p, const VolumeMesh* source) {
  VolumeMesh m = VolumeMesh::from_tets(p.V, p.T);
  const Eigen::Index n = source ? source->num_vertices() : 0;
  if (source && n <= p.V.rows() && p.V.topRows(n) == source->V) {
    for (const auto& [name, values] : source->point_data) {
      Eigen::MatrixXd padded = Eigen::MatrixXd::Zero(p.V.rows(), values.cols());
      padded.topRows(n) = values;
      m.point_data[name] = padded;
    }
    m.field_data = source->field_data;
  }
  attach_fields(m, p);
  for (int f = 0; f < 3; ++f) {
    m.cell_data[std::string("grad_") + kFieldNames[f]] = p.fields.gradients[f];
    m.cell_data[std::string("grad_") + kFieldNames[f] + "_initial"] = p.fields.gradients_initial[f];
  }
  return m;
}

MeshWriteOptions parameterized_model_writing() {
  MeshWriteOptions options;
  for (int f = 0; f < 3; ++f) {
    options.single_precision_arrays.insert(std::string("grad_") + kFieldNames[f]);
    options.single_precision_arrays.insert(std::string("grad_") + kFieldNames[f] + "_initial");
  }
  return options;
}

int exit_code(const QualitySummary& result) {
  return result.inverted + result.degenerate == 0 ? 0 : kExitUnusableCells;
}

}  // namespace facehex
