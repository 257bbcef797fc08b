#include "core/standard/own_feature_values.h"

#include "core/face/automatic_constraints.h"
#include "core/fields/parameterization.h"
#include "core/fields/tet_domain.h"
#include "core/mesh/tet_topology.h"
#include "core/standard/closed_domain.h"
#include "core/util/error.h"

namespace facehex {

std::map<std::string, double> own_feature_values(const VolumeMesh& model, double band, const std::string& source) {
  return own_feature_values(
      model, find_face_landmarks(model.V, side_mask_of(model), landmark_options_for(model, source)), band, source);
}

std::map<std::string, double> own_feature_values(const VolumeMesh& model, const FaceLandmarks& landmarks, double band,
                                                 const std::string& source) {
  const TetDomain domain = model.is_tet_mesh() ? own_domain(model) : closed_domain(model);
  HarmonicFieldsOptions plain;
  plain.orthogonality_iterations = 0;
  const ModelParameterization p =
      parameterize_model(domain.V, domain.T, domain.side_mask, side_constraints(), source, plain);
  std::map<std::string, double> placeholder;
  for (const auto& spec : feature_specs()) placeholder[spec.name] = 0.5;
  const ConstraintSet probe = feature_constraints(landmarks, placeholder, band);
  const std::vector<char> boundary =
      boundary_vertex_flags(static_cast<int>(domain.V.rows()), boundary_faces(domain.T).F);
  std::map<std::string, double> values;
  for (const auto& c : probe.constraints) {
    const std::vector<int> sel = select_vertices(c.select, domain.V, boundary, domain.side_mask);
    if (sel.empty()) throw Error(source, "feature '" + c.name + "' selects no vertex");
    double sum = 0;
    for (int v : sel) sum += p.fields.uvw(v, c.field);
    values[c.name] = c.field == 0 ? 0.5 : sum / static_cast<double>(sel.size());
  }
  return values;
}

}  // namespace facehex
