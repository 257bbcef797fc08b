#include "core/hex_transfer.h"

#include "core/param_locator.h"
#include "core/stopwatch.h"

namespace facehex {

VolumeMesh transfer_hex_mesh(const VolumeMesh& standard, const Eigen::MatrixXd& standard_uvw,
                             const Eigen::MatrixXd& patient_V, const Eigen::MatrixXi& patient_T,
                             const Eigen::MatrixXd& patient_uvw, TransferStatistics* statistics,
                             const ProgressCallback& progress) {
  TransferStatistics stats;
  Stopwatch clock;
  const ParamLocator locator(patient_uvw, patient_T);
  stats.seconds_locator_build = clock.lap();

  VolumeMesh out;
  out.C = standard.C;
  out.types = standard.types;
  out.V.resize(standard.V.rows(), 3);
  stats.vertices = static_cast<int>(standard.V.rows());
  stats.tet.resize(standard.V.rows());
  int hint = -1;
  for (Eigen::Index i = 0; i < standard.V.rows(); ++i) {
    if (i % 4096 == 0) report_progress(progress, "mapping vertices", static_cast<double>(i) / standard.V.rows());
    const Eigen::Vector3d q = standard_uvw.row(i).transpose();
    ParamLocator::Hit hit = locator.locate(q, hint);
    hint = hit.tet;
    stats.tet(i) = hit.tet;
    Eigen::Vector4d b = hit.bary;
    if (hit.violation > 0) {
      ++stats.located_nearest;
      stats.max_violation = std::max(stats.max_violation, hit.violation);
    } else {
      ++stats.located_inside;
    }
    // Weights of the patient tet's vertices that are not on the standard vertex's side(s) go to zero.
    bool on_side = false;
    Eigen::Vector4d on_side_weights = b;
    for (int d = 0; d < 3; ++d) {
      if (q(d) != 0.0 && q(d) != 1.0) continue;
      on_side = true;
      for (int k = 0; k < 4; ++k)
        if (patient_uvw(patient_T(hit.tet, k), d) != q(d)) on_side_weights(k) = 0;
    }
    on_side_weights = on_side_weights.cwiseMax(0.0);
    if (on_side && on_side_weights.sum() > 0) {
      b = on_side_weights;
      ++stats.snapped_to_boundary;
    } else {
      stats.snap_failures += on_side;
      b = b.cwiseMax(0.0);
    }
    b /= b.sum();
    Eigen::RowVector3d x = Eigen::RowVector3d::Zero();
    for (int k = 0; k < 4; ++k) x += b(k) * patient_V.row(patient_T(hit.tet, k));
    out.V.row(i) = x;
  }
  stats.seconds_mapping = clock.lap();
  stats.walk_hits = locator.walk_hits();
  if (statistics) *statistics = stats;
  return out;
}

}  // namespace facehex
