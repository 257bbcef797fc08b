#include "core/fields/parameterization.h"

namespace facehex {

ModelParameterization parameterize_model(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T,
                                         const Eigen::VectorXi& side_mask, const ConstraintSet& constraints,
                                         const std::string& source, const HarmonicFieldsOptions& options,
                                         const ProgressCallback& progress, const FieldConditions* added) {
  ResolvedConstraints resolved = resolve_constraints(constraints, V, T, side_mask, source);
  if (added)
    for (int f = 0; f < 3; ++f) {
      DirichletConditions& field = resolved.fields[f];
      std::vector<char> taken(static_cast<size_t>(V.rows()), 0);
      for (const int v : field.vertices) taken[v] = 1;
      const DirichletConditions& more = (*added)[f];
      for (size_t i = 0; i < more.vertices.size(); ++i)
        if (!taken[more.vertices[i]]) {
          taken[more.vertices[i]] = 1;
          field.vertices.push_back(more.vertices[i]);
          field.values.push_back(more.values[i]);
        }
    }
  const HarmonicFields fields(V, T, resolved, options, sub_progress(progress, 0.0, 0.3));
  return parameterization_of(V, T, std::move(resolved), fields.compute(sub_progress(progress, 0.3, 1.0)));
}

ModelParameterization parameterization_of(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T,
                                          ResolvedConstraints constraints, HarmonicFieldsResult fields) {
  ModelParameterization m;
  m.V = V;
  m.T = T;
  m.constraints = std::move(constraints);
  m.fixed = Eigen::MatrixXi::Zero(V.rows(), 3);
  for (int f = 0; f < 3; ++f)
    for (int v : m.constraints.fields[f].vertices) m.fixed(v, f) = 1;
  m.fields = std::move(fields);
  // The unit cube is the common domain: round-off can leave values a hair outside it.
  m.fields.uvw = m.fields.uvw.cwiseMax(0.0).cwiseMin(1.0);
  m.health = parameterization_health(T, m.fields.uvw, m.fixed);
  return m;
}

}  // namespace facehex
