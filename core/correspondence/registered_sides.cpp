#include "core/correspondence/registered_sides.h"

#include "core/correspondence/side_correspondence.h"
#include "core/fields/constraint_set.h"
#include "core/util/error.h"
#include "core/util/stopwatch.h"

namespace facehex {

RegisteredSides register_sides(const TetDomain& standard, const Eigen::MatrixXd& standard_uvw,
                               const VolumeMesh& patient, const std::string& patient_source,
                               const RegisteredSidesOptions& options, const PointPairs* landmarks,
                               const ProgressCallback& progress) {
  Stopwatch clock;
  if (standard.side_mask.size() != standard.V.rows() || standard_uvw.rows() != standard.V.rows())
    throw Error("registration", "the standard's domain has no side labels or no parameters at every vertex");
  VolumeMesh standard_mesh = VolumeMesh::from_tets(standard.V, standard.T);
  standard_mesh.point_data[kSideMaskArray] = standard.side_mask.cast<double>();
  const Eigen::MatrixXd registered = mesh_matching(standard_mesh, "the standard's domain", patient, patient_source,
                                                   options.registration, sub_progress(progress, 0.0, 0.9), landmarks)
                                         .hex.V;
  report_progress(progress, "pulling the standard's parameters back", 0.9);
  const Eigen::VectorXi patient_mask = side_mask_of(patient);
  RegisteredSides r;
  std::vector<double> distances;
  for (const Side side : options.sides) {
    const Eigen::MatrixXi F = side_triangles(standard.T, standard.side_mask, side);
    if (F.rows() == 0) throw Error("registration", std::string("the standard has no ") + kSideDescriptions[side]);
    const SideCorrespondence c = side_correspondence(registered, F, standard_uvw, patient.V, patient_mask, side);
    if (c.vertices.empty())
      throw Error(patient_source, std::string("no vertex on the ") + kSideDescriptions[side] +
                                      " alone: the registration has nothing to impose there");
    // The standard's side vertices that landed on the patient's side.
    const SurfaceLocator patient_side(patient.V, side_triangles(patient.tets(), patient_mask, side));
    std::vector<int> rows;
    for (int v = 0; v < standard.side_mask.size(); ++v)
      if (standard.side_mask(v) & side_bit(side)) rows.push_back(v);
    const Eigen::VectorXd landed = patient_side.closest(registered(rows, Eigen::all)).distance;
    r.standard_matched.resize(static_cast<size_t>(standard.V.rows()), 0);
    for (size_t i = 0; i < rows.size(); ++i)
      if (landed(static_cast<Eigen::Index>(i)) <= options.max_distance) r.standard_matched[rows[i]] = 1;
    for (size_t i = 0; i < c.vertices.size(); ++i) {
      const double d = c.distance(static_cast<Eigen::Index>(i));
      distances.push_back(d);
      if (!(d <= options.max_distance) || (c.on_rim[i] && d > options.rim_tolerance)) {
        ++r.vertices_too_far;
        continue;
      }
      for (int f = 0; f < 2; ++f) {
        r.conditions[f].vertices.push_back(c.vertices[i]);
        r.conditions[f].values.push_back(c.uvw(static_cast<Eigen::Index>(i), f));
      }
    }
  }
  r.distance = summarize_distances(
      Eigen::Map<const Eigen::VectorXd>(distances.data(), static_cast<Eigen::Index>(distances.size())));
  r.seconds = clock.lap();
  report_progress(progress, "pulling the standard's parameters back", 1.0);
  return r;
}

}  // namespace facehex
