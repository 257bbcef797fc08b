#include "core/transfer_pipeline.h"

#include "core/corner_jacobian.h"
#include "core/error.h"
#include "core/stopwatch.h"

#include <algorithm>
#include <memory>

namespace facehex {
namespace {

// Maps a sub-stage's progress into [lo, hi] of the whole run.
ProgressCallback sub_progress(const ProgressCallback& progress, double lo, double hi) {
  if (!progress) return {};
  return [=](const std::string& stage, double f) { return progress(stage, lo + (hi - lo) * f); };
}

std::string health_problem(const ParamHealth& h) {
  return std::to_string(h.inverted) + " of " + std::to_string(h.tets) + " parametric tets are inverted and " +
         std::to_string(h.degenerate - h.flat_by_constraint) +
         " degenerate (the fields fold); check the constraint set (sides, feature values) of this model";
}

// The untangler moves mapped standard vertices through their (u, v, w) and places them with the patient map: a
// coordinate pinned in the standard (a shape end: on the patient's boundary; a feature value: on its feature surface)
// stays pinned, so those vertices stay exactly on their side or feature.
VertexPlacement parametric_placement(const TransferRun& run, const PatientMap& patient, int hex_vertices) {
  VertexPlacement placement;
  placement.p = hex_vertex_uvw(run, hex_vertices);
  placement.movable.assign(hex_vertices, Eigen::Matrix3d::Identity());
  for (int v = 0; v < hex_vertices; ++v)
    for (int f = 0; f < 3; ++f)
      if (run.standard.fixed(v, f)) placement.movable[v](f, f) = 0;
  auto hints = std::make_shared<Eigen::VectorXi>(run.transfer.tet);
  placement.place = [&patient, hints](int v, const Eigen::Vector3d& q, Eigen::Vector3d& x, Eigen::Matrix3d& dxdq) {
    if ((q.array() < 0).any() || (q.array() > 1).any()) return false;  // outside the common domain
    const PatientMap::Placement p = patient.place(q, (*hints)(v));
    if (p.violation > 0) return false;
    (*hints)(v) = p.tet;
    x = p.x;
    dxdq = patient.jacobian(p.tet);
    return true;
  };
  return placement;
}

}  // namespace

ModelParameterization parameterize_model(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T,
                                         const Eigen::VectorXi& side_mask, const ConstraintSet& constraints,
                                         const std::string& source, const HarmonicFieldsOptions& options,
                                         const ProgressCallback& progress) {
  ModelParameterization m;
  m.V = V;
  m.T = T;
  m.constraints = resolve_constraints(constraints, V, T, side_mask, source);
  m.fixed = Eigen::MatrixXi::Zero(V.rows(), 3);
  for (int f = 0; f < 3; ++f)
    for (int v : m.constraints.fields[f].vertices) m.fixed(v, f) = 1;
  const HarmonicFields fields(V, T, m.constraints, options, sub_progress(progress, 0.0, 0.3));
  m.fields = fields.compute(sub_progress(progress, 0.3, 1.0));
  // The unit cube is the common domain: round-off can leave values a hair outside it.
  m.fields.uvw = m.fields.uvw.cwiseMax(0.0).cwiseMin(1.0);
  m.health = parameterization_health(T, m.fields.uvw, m.fixed);
  return m;
}

TransferRun run_transfer(const VolumeMesh& standard, const StandardDomain& domain,
                         const ConstraintSet& standard_constraints,
                         const std::string& standard_source, const VolumeMesh& patient,
                         const ConstraintSet& patient_constraints, const std::string& patient_source,
                         const TransferOptions& options, const ProgressCallback& progress) {
  TransferRun run;
  Stopwatch clock;
  if (domain.hex_vertices != standard.num_vertices() ||
      (domain.V.topRows(domain.hex_vertices) - standard.V).cwiseAbs().maxCoeff() > 0)
    throw Error(standard_source, "the parameterization domain was not built from this standard mesh");
  run.standard_domain = domain.description;
  run.standard_domain_non_positive = domain.non_positive_tets;
  run.standard = parameterize_model(domain.V, domain.T, domain.side_mask, standard_constraints, standard_source,
                                    options.fields, sub_progress(progress, 0.0, 0.3));
  run.seconds["standard_parameterization"] = clock.lap();
  run.patient = parameterize_model(patient.V, patient.tets(), side_mask_of(patient), patient_constraints,
                                   patient_source, options.fields, sub_progress(progress, 0.3, 0.85));
  run.seconds["patient_parameterization"] = clock.lap();

  const ParamHealth& health = run.patient.health;
  const int folded = health.inverted + health.degenerate - health.flat_by_constraint;
  if (!options.allow_inverted_parameterization && folded > options.max_inverted_fraction * health.tets)
    throw Error(patient_source, "parameterization: " + health_problem(health));
  if (run.standard.health.orientation != run.patient.health.orientation)
    throw Error(patient_source,
                "the model frame has the opposite handedness to the standard's (mirrored scan?): swap the u0 and u1 "
                "sides of its constraint set");
  const PatientMap patient_map(run.patient.V, run.patient.T, run.patient.fields.uvw);
  run.seconds["locator_build"] = clock.lap();
  run.patient_hex = transfer_hex_mesh(standard, hex_vertex_uvw(run, standard.num_vertices()), patient_map,
                                      &run.transfer, sub_progress(progress, 0.85, 1.0));
  run.seconds["mapping"] = clock.lap();
  if (options.untangle) {
    VertexPlacement placement = parametric_placement(run, patient_map, standard.num_vertices());
    // While inverted cells remain: widen the region that may move (a fold may need room beyond two rings), then
    // release the feature pins (never the sides) of the vertices of the cells still inverted: where the patient's
    // anatomy squeezes a feature (a flat nose), a valid element matters more than an exact feature line.
    UntangleOptions pass = options.untangle_options;
    run.untangle = untangle(run.patient_hex, placement, pass);
    for (int attempt = 0; attempt < 3 && run.untangle.inverted_after > 0; ++attempt) {
      if (attempt < 2) {
        pass.rings += 2;
      } else {
        const Eigen::MatrixXd uvw = hex_vertex_uvw(run, standard.num_vertices());
        for (int c : check_corner_jacobians(run.patient_hex).inverted)
          for (int i = 0; i < node_count(standard.types[c]); ++i) {
            const int v = standard.C(c, i);
            for (int f = 0; f < 3; ++f)
              if (uvw(v, f) != 0.0 && uvw(v, f) != 1.0) placement.movable[v](f, f) = 1;
            ++run.untangle.released_feature_vertices;
          }
      }
      const UntangleReport again = untangle(run.patient_hex, placement, pass);
      run.untangle.inverted_after = again.inverted_after;
      run.untangle.bad_after = again.bad_after;
      run.untangle.min_scaled_jacobian_after = again.min_scaled_jacobian_after;
      run.untangle.free_vertices = std::max(run.untangle.free_vertices, again.free_vertices);
      run.untangle.sweeps += again.sweeps;
    }
    if (run.untangle.inverted_after > 0) {
      // Last resort: the vertices of the cells still inverted move freely in space, even off their side by a
      // little (reported as side_vertex_distance), since a valid element matters more than an exact boundary there.
      std::vector<char> fixed(standard.num_vertices(), 1);
      for (int c : check_corner_jacobians(run.patient_hex).inverted)
        for (int i = 0; i < node_count(standard.types[c]); ++i) fixed[standard.C(c, i)] = 0;
      for (int v = 0; v < standard.num_vertices(); ++v) run.untangle.released_side_vertices += !fixed[v];
      VertexPlacement spatial = spatial_placement(run.patient_hex.V, fixed);
      const UntangleReport last = untangle(run.patient_hex, spatial, pass);
      run.untangle.inverted_after = last.inverted_after;
      run.untangle.bad_after = last.bad_after;
      run.untangle.min_scaled_jacobian_after = last.min_scaled_jacobian_after;
      run.untangle.sweeps += last.sweeps;
    }
    run.seconds["untangle"] = clock.lap();
  }
  return run;
}

Eigen::MatrixXd hex_vertex_uvw(const TransferRun& run, int hex_vertices) {
  return run.standard.fields.uvw.topRows(hex_vertices);
}

}  // namespace facehex
