#include "core/baseline/mesh_matching.h"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <unordered_map>

#include "core/baseline/landmark_snap.h"
#include "core/baseline/thin_plate_spline.h"
#include "core/fields/constraint_set.h"
#include "core/mesh/cell_faces.h"
#include "core/mesh/sides.h"
#include "core/mesh/tet_topology.h"
#include "core/quality/surface_distance.h"
#include "core/util/error.h"
#include "core/util/stopwatch.h"

namespace facehex {
namespace {

// The boundary of a volume mesh as triangles (quads split along a diagonal) with the sides each lies on.
struct LabelledSurface {
  Eigen::MatrixXi F;                                  // #F x 3 into the mesh's V
  std::array<Eigen::MatrixXi, kNumSides> side_F;      // the triangles of each side (all three corners on it)
  std::array<std::vector<int>, kNumSides> side_rows;  // their rows in F
  std::vector<int> labelled;                          // boundary vertices on at least one side
  Eigen::VectorXi mask;                               // #V side bits
};

LabelledSurface labelled_surface(const VolumeMesh& mesh, const std::string& source) {
  LabelledSurface s;
  s.mask = side_mask_of(mesh);
  if (s.mask.size() != mesh.num_vertices())
    throw Error(source, "no \"side_mask\" point data: mesh matching pairs the sides of the two models");
  if (mesh.is_tet_mesh()) {
    s.F = boundary_faces(mesh.tets()).F;  // the tets' own face sort, much faster on a large patient
  } else {
    std::vector<Eigen::Vector3i> tris;
    const FaceNeighbors neighbors = face_neighbors(mesh);
    for (int c = 0; c < mesh.num_cells(); ++c)
      for (int f = 0; f < static_cast<int>(neighbors[c].size()); ++f) {
        if (neighbors[c][f][0] >= 0) continue;
        const std::vector<int> v = face_vertices(mesh, c, f);
        tris.emplace_back(v[0], v[1], v[2]);
        if (v.size() == 4) tris.emplace_back(v[0], v[2], v[3]);
      }
    s.F.resize(static_cast<Eigen::Index>(tris.size()), 3);
    for (size_t t = 0; t < tris.size(); ++t) s.F.row(static_cast<Eigen::Index>(t)) = tris[t].transpose();
  }
  const std::vector<char> on_boundary = boundary_vertex_flags(mesh.num_vertices(), s.F);
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (on_boundary[v] && s.mask(v) != 0) s.labelled.push_back(v);
  for (int side = 0; side < kNumSides; ++side) {
    const int bit = side_bit(static_cast<Side>(side));
    for (Eigen::Index t = 0; t < s.F.rows(); ++t)
      if ((s.mask(s.F(t, 0)) & s.mask(s.F(t, 1)) & s.mask(s.F(t, 2)) & bit) != 0)
        s.side_rows[side].push_back(static_cast<int>(t));
    s.side_F[side].resize(static_cast<Eigen::Index>(s.side_rows[side].size()), 3);
    for (size_t i = 0; i < s.side_rows[side].size(); ++i)
      s.side_F[side].row(static_cast<Eigen::Index>(i)) = s.F.row(s.side_rows[side][i]);
  }
  if (s.labelled.empty()) throw Error(source, "no boundary vertex lies on a side (\"side_mask\" is all zero)");
  return s;
}

// The frame assumption of mesh_matching.h: the skin (w1) lies in front (+y) of the bone side (w0).
void check_frame(const VolumeMesh& mesh, const Eigen::VectorXi& mask, const std::string& source) {
  double y[2] = {0, 0};
  int n[2] = {0, 0};
  for (int v = 0; v < mesh.num_vertices(); ++v)
    for (int i = 0; i < 2; ++i)
      if (mask(v) & side_bit(i == 0 ? W0 : W1)) {
        y[i] += mesh.V(v, 1);
        ++n[i];
      }
  if (n[0] == 0 || n[1] == 0)
    throw Error(source, "mesh matching needs vertices on both the bone (w0) and skin (w1) sides");
  if (y[1] / n[1] <= y[0] / n[0])
    throw Error(source,
                "the skin side (w1) does not lie in front (+y) of the bone side (w0): mesh matching assumes "
                "the face looks to +y with +z up (reorient the model)");
}

// About `target` of the candidate rows of V, one per cell of a uniform grid (the one nearest the cell's centre).
std::vector<int> grid_subsample(const Eigen::MatrixXd& V, const std::vector<int>& candidates, int target) {
  if (static_cast<int>(candidates.size()) <= target) return candidates;
  Eigen::RowVector3d lo = V.row(candidates[0]), hi = lo;
  for (int v : candidates) {
    lo = lo.cwiseMin(V.row(v));
    hi = hi.cwiseMax(V.row(v));
  }
  auto sample = [&](double h) {
    std::unordered_map<long long, std::pair<int, double>> best;  // cell -> (vertex, squared distance to centre)
    for (int v : candidates) {
      const Eigen::RowVector3d g = (V.row(v) - lo) / h;
      const long long i = static_cast<long long>(g(0)), j = static_cast<long long>(g(1)),
                      k = static_cast<long long>(g(2));
      const double d2 = (g - Eigen::RowVector3d(i + 0.5, j + 0.5, k + 0.5)).squaredNorm();
      const long long key = (i * 1000003LL + j) * 1000003LL + k;
      const auto it = best.find(key);
      if (it == best.end() || d2 < it->second.second) best[key] = {v, d2};
    }
    std::vector<int> out;
    for (const auto& [key, b] : best) out.push_back(b.first);
    std::sort(out.begin(), out.end());
    return out;
  };
  // Samples of a surface scale as h^-2: a few secant steps on h.
  double h = (hi - lo).norm() / std::sqrt(static_cast<double>(target));
  std::vector<int> out = sample(h);
  for (int step = 0; step < 8 && std::abs(static_cast<double>(out.size()) / target - 1) > 0.1; ++step) {
    h *= std::sqrt(static_cast<double>(out.size()) / target);
    out = sample(h);
  }
  return out;
}

struct Pairs {
  Eigen::MatrixXd source, target;                           // #M x 3
  Eigen::VectorXd weight;                                   // #M, sums to 1
  double standard_to_patient = 0, patient_to_standard = 0;  // mean distances (mm)
};

// The closest point of each query point on the triangles of its sides (the nearest over all its side bits).
struct SideHits {
  SurfaceLocator::Hits hits;  // face: a row of the whole surface's F, or -1
  Eigen::VectorXi side;       // #P, the side of the closest point, or -1
};

SideHits closest_on_sides(const Eigen::MatrixXd& X, const std::vector<int>& query, const Eigen::VectorXi& mask,
                          const std::array<std::unique_ptr<SurfaceLocator>, kNumSides>& locators,
                          const std::array<std::vector<int>, kNumSides>& side_rows) {
  const Eigen::Index n = static_cast<Eigen::Index>(query.size());
  SideHits best{{Eigen::MatrixXd::Zero(n, 3), Eigen::VectorXi::Constant(n, -1),
                 Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity())},
                Eigen::VectorXi::Constant(n, -1)};
  for (int side = 0; side < kNumSides; ++side) {
    std::vector<Eigen::Index> rows;
    for (Eigen::Index i = 0; i < n; ++i)
      if (mask(query[i]) & side_bit(static_cast<Side>(side))) rows.push_back(i);
    if (rows.empty() || side_rows[side].empty()) continue;
    Eigen::MatrixXd points(static_cast<Eigen::Index>(rows.size()), 3);
    for (size_t r = 0; r < rows.size(); ++r) points.row(static_cast<Eigen::Index>(r)) = X.row(query[rows[r]]);
    const SurfaceLocator::Hits hits = locators[side]->closest(points);
    for (size_t r = 0; r < rows.size(); ++r) {
      const Eigen::Index i = rows[r], h = static_cast<Eigen::Index>(r);
      if (hits.face(h) < 0 || hits.distance(h) >= best.hits.distance(i)) continue;
      best.hits.point.row(i) = hits.point.row(h);
      best.hits.face(i) = side_rows[side][hits.face(h)];
      best.hits.distance(i) = hits.distance(h);
      best.side(i) = side;
    }
  }
  return best;
}

// Keeps a direction's pairs up to `outlier` times the median distance of the pairs on the same side (sides differ in
// size, and a small side, such as a cut, must not be dropped as a whole), each with weight 0.5 / kept.
void append_inliers(Pairs& pairs, const Eigen::MatrixXd& source, const Eigen::MatrixXd& target, const SideHits& hits,
                    double outlier) {
  std::array<double, kNumSides> limit{};
  for (int side = 0; side < kNumSides; ++side) {
    std::vector<double> d;
    for (Eigen::Index i = 0; i < hits.side.size(); ++i)
      if (hits.side(i) == side) d.push_back(hits.hits.distance(i));
    if (d.empty()) continue;
    std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
    limit[side] = outlier * d[d.size() / 2];
  }
  std::vector<Eigen::Index> order;
  for (Eigen::Index i = 0; i < hits.side.size(); ++i)
    if (hits.side(i) >= 0 && hits.hits.distance(i) <= limit[hits.side(i)]) order.push_back(i);
  const Eigen::Index old = pairs.source.rows(), add = static_cast<Eigen::Index>(order.size());
  pairs.source.conservativeResize(old + add, 3);
  pairs.target.conservativeResize(old + add, 3);
  pairs.weight.conservativeResize(old + add);
  for (Eigen::Index k = 0; k < add; ++k) {
    pairs.source.row(old + k) = source.row(order[k]);
    pairs.target.row(old + k) = target.row(order[k]);
    pairs.weight(old + k) = 0.5 / static_cast<double>(add);
  }
}

// The registration state shared by both stages: the standard's source positions (#Vs x 3, fixed per stage), the
// current map applied to them, and the symmetric side-aware pairs at the current positions.
class Matcher {
 public:
  Matcher(const VolumeMesh& standard, const LabelledSurface& standard_surface, const VolumeMesh& patient,
          const LabelledSurface& patient_surface, const MeshMatchingOptions& options)
      : standard_(standard_surface), patient_V_(patient.V), patient_(patient_surface), options_(options) {
    for (int side = 0; side < kNumSides; ++side)
      patient_locators_[side] = std::make_unique<SurfaceLocator>(patient.V, patient_surface.side_F[side]);
    standard_samples_ = grid_subsample(standard.V, standard_surface.labelled, options.pairs_per_direction);
    patient_samples_ = grid_subsample(patient.V, patient_surface.labelled, options.pairs_per_direction);
  }

  // sources: #Vs x 3 positions the map is fitted from; current: #Vs x 3 their current images; landmark_sources: the
  // standard's landmarks in the frame of `sources` (#L x 3, or empty), paired with landmarks.patient.
  Pairs pairs(const Eigen::MatrixXd& sources, const Eigen::MatrixXd& current, const PointPairs& landmarks = {},
              const Eigen::MatrixXd& landmark_sources = Eigen::MatrixXd()) const {
    Pairs pairs;
    pairs.source.resize(0, 3);
    pairs.target.resize(0, 3);
    // Standard -> patient: each sampled standard vertex to the patient's surface of its sides.
    const SideHits forward =
        closest_on_sides(current, standard_samples_, standard_.mask, patient_locators_, patient_.side_rows);
    Eigen::MatrixXd from(static_cast<Eigen::Index>(standard_samples_.size()), 3);
    for (size_t i = 0; i < standard_samples_.size(); ++i)
      from.row(static_cast<Eigen::Index>(i)) = sources.row(standard_samples_[i]);
    append_inliers(pairs, from, forward.hits.point, forward, options_.outlier_factor);
    pairs.standard_to_patient = finite_mean(forward.hits.distance);
    // Patient -> standard: each sampled patient vertex to the current standard surface of its sides.
    std::array<std::unique_ptr<SurfaceLocator>, kNumSides> standard_locators;
    for (int side = 0; side < kNumSides; ++side)
      standard_locators[side] = std::make_unique<SurfaceLocator>(current, standard_.side_F[side]);
    const SideHits backward =
        closest_on_sides(patient_V_, patient_samples_, patient_.mask, standard_locators, standard_.side_rows);
    const Eigen::Index n = static_cast<Eigen::Index>(patient_samples_.size());
    Eigen::MatrixXd source(n, 3), target(n, 3);
    for (Eigen::Index i = 0; i < n; ++i) {
      target.row(i) = patient_V_.row(patient_samples_[i]);
      source.row(i).setZero();
      if (backward.hits.face(i) < 0) continue;
      const Eigen::RowVector3i t = standard_.F.row(backward.hits.face(i));
      const Eigen::Vector3d l =
          triangle_barycentric(backward.hits.point.row(i), current.row(t(0)), current.row(t(1)), current.row(t(2)));
      for (int k = 0; k < 3; ++k) source.row(i) += l(k) * sources.row(t(k));
    }
    append_inliers(pairs, source, target, backward, options_.outlier_factor);
    pairs.patient_to_standard = finite_mean(backward.hits.distance);
    if (landmark_sources.rows() > 0) {
      const Eigen::Index old = pairs.source.rows(), add = landmark_sources.rows();
      pairs.weight *= 1 - landmarks.weight;
      pairs.source.conservativeResize(old + add, 3);
      pairs.target.conservativeResize(old + add, 3);
      pairs.weight.conservativeResize(old + add);
      pairs.source.bottomRows(add) = landmark_sources;
      pairs.target.bottomRows(add) = landmarks.patient;
      pairs.weight.tail(add).setConstant(landmarks.weight / static_cast<double>(add));
    }
    if (pairs.source.rows() < 8)
      throw Error("mesh matching", "the two models share no side to pair (check their \"side_mask\" labels)");
    return pairs;
  }

 private:
  static double finite_mean(const Eigen::VectorXd& d) {
    double sum = 0;
    int n = 0;
    for (const double x : d)
      if (std::isfinite(x)) {
        sum += x;
        ++n;
      }
    return n ? sum / n : 0;
  }

  const LabelledSurface& standard_;
  const Eigen::MatrixXd& patient_V_;
  const LabelledSurface& patient_;
  const MeshMatchingOptions& options_;
  std::array<std::unique_ptr<SurfaceLocator>, kNumSides> patient_locators_;
  std::vector<int> standard_samples_, patient_samples_;
};

// The similarity x -> s R x + t minimizing sum_j w_j |s R p_j + t - q_j|^2 (Umeyama 1991, weighted).
struct Similarity {
  double s = 1;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::RowVector3d t = Eigen::RowVector3d::Zero();
  Eigen::MatrixXd operator()(const Eigen::MatrixXd& X) const { return ((s * X * R.transpose()).rowwise() + t); }
};

Similarity fit_similarity(const Pairs& p) {
  const Eigen::RowVector3d mp = p.weight.transpose() * p.source, mq = p.weight.transpose() * p.target;
  const Eigen::MatrixXd P = p.source.rowwise() - mp, Q = p.target.rowwise() - mq;
  const Eigen::Matrix3d cov = Q.transpose() * p.weight.asDiagonal() * P;  // sum w q p^T
  const double var_p = (P.rowwise().squaredNorm().transpose() * p.weight)(0);
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(cov, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Vector3d d = Eigen::Vector3d::Ones();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0) d(2) = -1;
  Similarity sim;
  sim.R = svd.matrixU() * d.asDiagonal() * svd.matrixV().transpose();
  sim.s = var_p > 0 ? svd.singularValues().dot(d) / var_p : 1;
  sim.t = mq - sim.s * mp * sim.R.transpose();
  return sim;
}

}  // namespace

MeshMatchingResult mesh_matching(const VolumeMesh& standard, const std::string& standard_source,
                                 const VolumeMesh& patient, const std::string& patient_source,
                                 const MeshMatchingOptions& options, const ProgressCallback& progress,
                                 const PointPairs* landmarks) {
  MeshMatchingResult result;
  const PointPairs known = landmarks ? *landmarks : PointPairs{};
  if (known.standard.rows() != known.patient.rows() || (known.standard.rows() > 0 && known.standard.cols() != 3) ||
      (known.patient.rows() > 0 && known.patient.cols() != 3))
    throw Error("mesh matching", "the landmark pairs are not two lists of the same number of 3D points");
  Stopwatch clock;
  const LabelledSurface standard_surface = labelled_surface(standard, standard_source);
  const LabelledSurface patient_surface = labelled_surface(patient, patient_source);
  check_frame(standard, standard_surface.mask, standard_source);
  check_frame(patient, patient_surface.mask, patient_source);
  const Matcher matcher(standard, standard_surface, patient, patient_surface, options);
  result.seconds["surfaces"] = clock.lap();

  // 1. Similarity, from the bounding boxes, then iterated closest points.
  const Eigen::RowVector3d slo = standard.V.colwise().minCoeff(), shi = standard.V.colwise().maxCoeff();
  const Eigen::RowVector3d plo = patient.V.colwise().minCoeff(), phi = patient.V.colwise().maxCoeff();
  Similarity sim;
  sim.s = std::cbrt((phi - plo).prod() / (shi - slo).prod());
  sim.t = 0.5 * (plo + phi) - sim.s * 0.5 * (slo + shi);
  // Each stage (the similarity, then each stiffness) iterates until the mean pair distance improves by less than
  // options.convergence, at most its iteration budget.
  const double budget =
      options.similarity_iterations + static_cast<double>(options.stiffness.size() * options.iterations_per_stiffness);
  int step = 0;
  auto converged = [&](int it) {
    const size_t n = result.iterations.size();
    if (it < 2) return false;
    const auto mean = [&](size_t i) {
      return result.iterations[i].standard_to_patient_mm + result.iterations[i].patient_to_standard_mm;
    };
    return mean(n - 2) - mean(n - 1) < options.convergence * mean(n - 2);
  };
  for (int it = 0; it < options.similarity_iterations; ++it, ++step) {
    report_progress(progress, "mesh matching: similarity", step / budget);
    const Pairs pairs = matcher.pairs(standard.V, sim(standard.V), known, known.standard);
    result.iterations.push_back({"similarity", 0, pairs.standard_to_patient, pairs.patient_to_standard});
    if (converged(it)) break;
    sim = fit_similarity(pairs);
  }
  result.scale = sim.s;
  const Eigen::MatrixXd aligned = sim(standard.V);
  const Eigen::MatrixXd aligned_landmarks = known.standard.rows() > 0 ? sim(known.standard) : Eigen::MatrixXd();
  result.seconds["similarity"] = clock.lap();

  // 2. Thin-plate spline from the aligned standard, stiff to soft.
  const std::vector<int> controls = grid_subsample(aligned, standard_surface.labelled, options.control_points);
  Eigen::MatrixXd C(static_cast<Eigen::Index>(controls.size()), 3);
  for (size_t i = 0; i < controls.size(); ++i) C.row(static_cast<Eigen::Index>(i)) = aligned.row(controls[i]);
  result.control_points = static_cast<int>(controls.size());
  ThinPlateSpline spline(C);
  for (const double stiffness : options.stiffness)
    for (int it = 0; it < options.iterations_per_stiffness; ++it, ++step) {
      report_progress(progress, "mesh matching: thin-plate spline", std::min(1.0, step / budget));
      const Pairs pairs = matcher.pairs(aligned, spline(aligned), known, aligned_landmarks);
      result.iterations.push_back({"spline", stiffness, pairs.standard_to_patient, pairs.patient_to_standard});
      if (converged(it)) break;
      spline.fit(pairs.source, pairs.target, pairs.weight, stiffness);
    }
  result.seconds["spline"] = clock.lap();

  // 3. Every node.
  result.hex = standard;
  result.hex.V = spline(aligned);
  if (known.snap_radius > 0 && known.standard.rows() > 0)
    result.hex.V = landmark_snap(result.hex.V, spline(aligned_landmarks), known.patient, known.snap_radius);
  result.seconds["apply"] = clock.lap();
  report_progress(progress, "mesh matching: done", 1.0);
  return result;
}

}  // namespace facehex
