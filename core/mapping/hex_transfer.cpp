#include "core/mapping/hex_transfer.h"

#include <Eigen/Dense>

#include "core/util/stopwatch.h"

namespace facehex {

PatientMap::PatientMap(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, const Eigen::MatrixXd& uvw)
    : V_(V), T_(T), uvw_(uvw), locator_(uvw, T) {}

PatientMap::Placement PatientMap::place(const Eigen::Vector3d& q, int hint) const {
  const ParamLocator::Hit hit = locator_.locate(q, hint);
  Placement p;
  p.tet = hit.tet;
  p.violation = hit.violation;
  Eigen::Vector4d b = hit.bary;
  // Weights of the patient tet's vertices that are not on q's side(s) go to zero (they are zero up to round-off).
  bool on_side = false;
  Eigen::Vector4d on_side_weights = b;
  for (int d = 0; d < 3; ++d) {
    if (q(d) != 0.0 && q(d) != 1.0) continue;
    on_side = true;
    for (int k = 0; k < 4; ++k)
      if (uvw_(T_(hit.tet, k), d) != q(d)) on_side_weights(k) = 0;
  }
  on_side_weights = on_side_weights.cwiseMax(0.0);
  if (on_side && on_side_weights.sum() > 0) {
    b = on_side_weights;
    p.snapped = true;
  } else {
    p.snap_failed = on_side;
    b = b.cwiseMax(0.0);
  }
  b /= b.sum();
  p.x.setZero();
  for (int k = 0; k < 4; ++k) p.x += b(k) * V_.row(T_(hit.tet, k)).transpose();
  return p;
}

Eigen::Matrix3d PatientMap::jacobian(int tet) const {
  Eigen::Matrix3d dX, dQ;  // columns: edges from vertex 0 in space and in the parameter cube
  for (int k = 0; k < 3; ++k) {
    dX.col(k) = (V_.row(T_(tet, k + 1)) - V_.row(T_(tet, 0))).transpose();
    dQ.col(k) = (uvw_.row(T_(tet, k + 1)) - uvw_.row(T_(tet, 0))).transpose();
  }
  return dX * dQ.inverse();
}

VolumeMesh transfer_hex_mesh(const VolumeMesh& standard, const Eigen::MatrixXd& standard_uvw, const PatientMap& patient,
                             TransferStatistics* statistics, const ProgressCallback& progress) {
  TransferStatistics stats;
  Stopwatch clock;
  VolumeMesh out;
  out.C = standard.C;
  out.types = standard.types;
  out.V.resize(standard.V.rows(), 3);
  stats.vertices = static_cast<int>(standard.V.rows());
  stats.tet.resize(standard.V.rows());
  const int walks_before = patient.locator().walk_hits();
  int hint = -1;
  for (Eigen::Index i = 0; i < standard.V.rows(); ++i) {
    if (i % 4096 == 0) report_progress(progress, "mapping vertices", static_cast<double>(i) / standard.V.rows());
    const PatientMap::Placement p = patient.place(standard_uvw.row(i).transpose(), hint);
    hint = p.tet;
    stats.tet(i) = p.tet;
    if (p.violation > 0) {
      ++stats.located_nearest;
      stats.max_violation = std::max(stats.max_violation, p.violation);
    } else {
      ++stats.located_inside;
    }
    stats.snapped_to_boundary += p.snapped;
    stats.snap_failures += p.snap_failed;
    out.V.row(i) = p.x.transpose();
  }
  stats.seconds_mapping = clock.lap();
  stats.walk_hits = patient.locator().walk_hits() - walks_before;
  if (statistics) *statistics = stats;
  return out;
}

}  // namespace facehex
