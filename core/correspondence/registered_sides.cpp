#include "core/correspondence/registered_sides.h"

#include <algorithm>
#include <array>
#include <unordered_map>

#include "core/correspondence/side_correspondence.h"
#include "core/fields/constraint_set.h"
#include "core/util/error.h"
#include "core/util/stopwatch.h"

namespace facehex {
namespace {

// The patient's side triangle under each landmark (its closest point there) gets, at its three vertices, the
// standard's (u, v) at their correspondents shifted by one offset so that, interpolated at the landmark, they are the
// standard's landmark vertex's own: the harmonic fields then put that vertex exactly on the landmark. Returns how many
// landmarks were pinned: those whose standard point is a domain vertex and whose triangle's vertices all have a
// correspondent (c).
int pin_landmarks(const PointPairs& landmarks, const Eigen::MatrixXd& standard_V, const Eigen::MatrixXd& standard_uvw,
                  const Eigen::MatrixXd& patient_V, const Eigen::MatrixXi& patient_F,
                  const SurfaceLocator& patient_side, const SideCorrespondence& c, FieldConditions& conditions) {
  if (landmarks.patient.rows() == 0 || patient_F.rows() == 0) return 0;
  std::unordered_map<int, Eigen::Index> row_of;  // patient vertex -> its row in c
  for (size_t i = 0; i < c.vertices.size(); ++i) row_of[c.vertices[i]] = static_cast<Eigen::Index>(i);
  std::array<std::unordered_map<int, size_t>, 2> condition_of;
  for (int f = 0; f < 2; ++f)
    for (size_t k = 0; k < conditions[f].vertices.size(); ++k) condition_of[f][conditions[f].vertices[k]] = k;
  const SurfaceLocator::Hits hits = patient_side.closest(landmarks.patient);
  int pinned = 0;
  for (Eigen::Index l = 0; l < landmarks.patient.rows(); ++l) {
    Eigen::Index vertex = -1;
    (standard_V.rowwise() - landmarks.standard.row(l)).rowwise().squaredNorm().minCoeff(&vertex);
    if ((standard_V.row(vertex) - landmarks.standard.row(l)).norm() > 1e-9) continue;
    const Eigen::Vector3i tri = patient_F.row(hits.face(l)).transpose();
    if (!row_of.count(tri(0)) || !row_of.count(tri(1)) || !row_of.count(tri(2))) continue;
    const Eigen::Vector3d b =
        triangle_barycentric(hits.point.row(l), patient_V.row(tri(0)), patient_V.row(tri(1)), patient_V.row(tri(2)));
    for (int f = 0; f < 2; ++f) {
      double at = 0;
      for (int k = 0; k < 3; ++k) at += b(k) * c.uvw(row_of.at(tri(k)), f);
      const double offset = standard_uvw(vertex, f) - at;
      for (int k = 0; k < 3; ++k) {
        const double value = std::clamp(c.uvw(row_of.at(tri(k)), f) + offset, 0.0, 1.0);
        const auto known = condition_of[f].find(tri(k));
        if (known != condition_of[f].end()) {
          conditions[f].values[known->second] = value;
        } else {
          condition_of[f][tri(k)] = conditions[f].vertices.size();
          conditions[f].vertices.push_back(tri(k));
          conditions[f].values.push_back(value);
        }
      }
    }
    ++pinned;
  }
  return pinned;
}

}  // namespace

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
    const Eigen::MatrixXi patient_F = side_triangles(patient.tets(), patient_mask, side);
    const SurfaceLocator patient_side(patient.V, patient_F);
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
    if (side == W1 && landmarks && landmarks->snap_radius > 0)  // facial landmarks lie on the skin
      r.pinned_landmarks +=
          pin_landmarks(*landmarks, standard.V, standard_uvw, patient.V, patient_F, patient_side, c, r.conditions);
  }
  r.distance = summarize_distances(
      Eigen::Map<const Eigen::VectorXd>(distances.data(), static_cast<Eigen::Index>(distances.size())));
  r.seconds = clock.lap();
  report_progress(progress, "pulling the standard's parameters back", 1.0);
  return r;
}

}  // namespace facehex
