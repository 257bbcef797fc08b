#include "core/mapping/param_locator.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "core/mesh/tet_topology.h"

namespace facehex {

ParamLocator::ParamLocator(const Eigen::MatrixXd& P, const Eigen::MatrixXi& T)
    : P_(P), T_(T), neighbors_(tet_face_neighbors(T)), usable_(T.rows(), 0) {
  const Eigen::Index nt = T.rows();
  lo_ = P.colwise().minCoeff().transpose();
  const Eigen::Vector3d hi = P.colwise().maxCoeff().transpose();
  // About two tets per grid cell on average, at most 256 cells per axis.
  const int n = std::clamp(static_cast<int>(std::cbrt(static_cast<double>(nt) / 2.0)), 1, 256);
  dims_ = Eigen::Vector3i::Constant(n);
  cell_size_ = ((hi - lo_).array().max(1e-12) / n).matrix();

  double mean_abs_det = 0;
  std::vector<double> dets(nt);
  for (Eigen::Index t = 0; t < nt; ++t) {
    Eigen::Matrix3d D;
    for (int k = 0; k < 3; ++k) D.col(k) = (P.row(T(t, k + 1)) - P.row(T(t, 0))).transpose();
    dets[t] = D.determinant();
    mean_abs_det += std::abs(dets[t]) / static_cast<double>(nt);
  }
  for (Eigen::Index t = 0; t < nt; ++t) usable_[t] = std::abs(dets[t]) > 1e-12 * mean_abs_det;

  // Two passes (count, fill) over each usable tet's bounding box of grid cells.
  std::vector<Eigen::Vector3i> box_lo(nt), box_hi(nt);
  cell_start_.assign(static_cast<size_t>(dims_.prod()) + 1, 0);
  for (Eigen::Index t = 0; t < nt; ++t) {
    if (!usable_[t]) continue;
    Eigen::Vector3d tlo = P.row(T(t, 0)), thi = tlo;
    for (int k = 1; k < 4; ++k) {
      tlo = tlo.cwiseMin(P.row(T(t, k)).transpose());
      thi = thi.cwiseMax(P.row(T(t, k)).transpose());
    }
    box_lo[t] = cell_of(tlo);
    box_hi[t] = cell_of(thi);
    for (int k = box_lo[t].z(); k <= box_hi[t].z(); ++k)
      for (int j = box_lo[t].y(); j <= box_hi[t].y(); ++j)
        for (int i = box_lo[t].x(); i <= box_hi[t].x(); ++i) ++cell_start_[cell_index(i, j, k) + 1];
  }
  for (size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  cell_tets_.resize(cell_start_.back());
  std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (Eigen::Index t = 0; t < nt; ++t) {
    if (!usable_[t]) continue;
    for (int k = box_lo[t].z(); k <= box_hi[t].z(); ++k)
      for (int j = box_lo[t].y(); j <= box_hi[t].y(); ++j)
        for (int i = box_lo[t].x(); i <= box_hi[t].x(); ++i)
          cell_tets_[fill[cell_index(i, j, k)]++] = static_cast<int>(t);
  }
}

Eigen::Vector3i ParamLocator::cell_of(const Eigen::Vector3d& q) const {
  Eigen::Vector3i c;
  for (int d = 0; d < 3; ++d)
    c(d) = std::clamp(static_cast<int>(std::floor((q(d) - lo_(d)) / cell_size_(d))), 0, dims_(d) - 1);
  return c;
}

bool ParamLocator::barycentric(int t, const Eigen::Vector3d& q, Eigen::Vector4d& bary) const {
  if (!usable_[t]) return false;
  const Eigen::Vector3d p0 = P_.row(T_(t, 0));
  const Eigen::Vector3d a = P_.row(T_(t, 1)).transpose() - p0, b = P_.row(T_(t, 2)).transpose() - p0,
                        c = P_.row(T_(t, 3)).transpose() - p0, d = q - p0;
  // Cramer's rule by triple products: the tet is not degenerate (usable_), so det is well away from zero.
  const Eigen::Vector3d bc = b.cross(c);
  const double inv_det = 1.0 / a.dot(bc);
  const Eigen::Vector3d l(d.dot(bc) * inv_det, a.dot(d.cross(c)) * inv_det, a.dot(b.cross(d)) * inv_det);
  bary << 1.0 - l.sum(), l;
  return true;
}

ParamLocator::Hit ParamLocator::locate(const Eigen::Vector3d& q, int hint) const {
  constexpr double kInside = -1e-12;
  Hit best;
  best.violation = std::numeric_limits<double>::infinity();
  // A tet overlaps several grid cells: the grid's search tries each once per query (stamps per thread: the untangler
  // locates from several threads).
  thread_local std::vector<unsigned> tried;
  thread_local unsigned query = 0;
  auto consider = [&](int t) {
    if (tried[t] == query) return false;
    tried[t] = query;
    Eigen::Vector4d b;
    if (!barycentric(t, q, b)) return false;
    const double v = std::max(0.0, -b.minCoeff());
    if (v < best.violation) best = {t, b, v};
    return b.minCoeff() >= kInside;
  };

  // Walk towards q across the face with the most negative barycentric coordinate.
  if (hint >= 0 && hint < T_.rows()) {
    int t = hint;
    for (int step = 0; step < 64 && t >= 0 && usable_[t]; ++step) {
      Eigen::Vector4d b;
      barycentric(t, q, b);
      if (b.minCoeff() >= kInside) {
        ++walk_hits_;
        return {t, b, 0.0};
      }
      int exit_face = 0;
      b.minCoeff(&exit_face);
      t = neighbors_(t, exit_face);
    }
  }

  // Grid: the cell of q, then growing shells of cells around it while nothing contains q.
  if (tried.size() < static_cast<size_t>(T_.rows())) tried.assign(T_.rows(), 0);
  if (++query == 0) {  // the stamps wrapped around
    std::fill(tried.begin(), tried.end(), 0);
    query = 1;
  }
  const Eigen::Vector3i c = cell_of(q);
  const int max_ring = std::max(2, dims_.maxCoeff() / 8);
  for (int ring = 0; ring <= max_ring; ++ring) {
    for (int k = c.z() - ring; k <= c.z() + ring; ++k)
      for (int j = c.y() - ring; j <= c.y() + ring; ++j)
        for (int i = c.x() - ring; i <= c.x() + ring; ++i) {
          if (i < 0 || j < 0 || k < 0 || i >= dims_.x() || j >= dims_.y() || k >= dims_.z()) continue;
          if (std::max({std::abs(i - c.x()), std::abs(j - c.y()), std::abs(k - c.z())}) != ring) continue;
          const int cell = cell_index(i, j, k);
          for (int s = cell_start_[cell]; s < cell_start_[cell + 1]; ++s)
            if (consider(cell_tets_[s])) return {best.tet, best.bary, 0.0};
        }
    if (best.tet >= 0 && ring >= 1) break;  // nearest candidates seen: take the least violating one
  }
  return best;
}

}  // namespace facehex
