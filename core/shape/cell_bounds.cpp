#include "core/shape/cell_bounds.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "core/mesh/corner_jacobian.h"
#include "core/shape/corner_energy.h"
#include "core/util/error.h"

namespace facehex {
namespace {
constexpr double kReferenceShare = 0.5;  // see UntangleOptions::reference_scaled_jacobian
}

CellBounds::CellBounds(const VolumeMesh& mesh, const UntangleOptions& options) : options_(options) {
  const int nc = mesh.num_cells();
  if (options.reference_scaled_jacobian.size() != 0 && options.reference_scaled_jacobian.size() != nc)
    throw Error("shape solver", "the reference scaled Jacobians do not match the mesh's cells");
  if (options.target && (options.target->num_cells() != nc || options.target->types != mesh.types ||
                         options.target->C.cols() != mesh.C.cols() || options.target->C != mesh.C))
    throw Error("shape solver", "the target mesh does not have the mesh's cells");
}

double CellBounds::bound(int c) const {
  return options_.reference_scaled_jacobian.size() == 0
             ? options_.min_scaled_jacobian
             : std::min(options_.min_scaled_jacobian, kReferenceShare * options_.reference_scaled_jacobian(c));
}

bool CellBounds::is_bad(const VolumeMesh& mesh, int c) const {
  const CellJacobians j = cell_jacobians(mesh.types[c], cell_nodes(mesh, c));
  return j.min_determinant <= 0 || j.scaled_jacobian < bound(c);
}

CellBounds::Counts CellBounds::count(const VolumeMesh& mesh) const {
  Counts counts;
  for (int c = 0; c < mesh.num_cells(); ++c) {
    const CellJacobians j = cell_jacobians(mesh.types[c], cell_nodes(mesh, c));
    const bool inverted = j.min_determinant <= 0;
    counts.inverted += inverted;
    counts.degenerate += !inverted && is_unusable(j);
    counts.bad += inverted || j.scaled_jacobian < bound(c);
    counts.min_scaled_jacobian = std::min(counts.min_scaled_jacobian, j.scaled_jacobian);
  }
  return counts;
}

Eigen::Matrix3d slot_matrix(CellType type, const CellNodes& X, int slot) {
  return slot >= kSampleSlot ? (X.transpose() * interior_sample_weights(type)[slot - kSampleSlot]).eval()
                             : corner_jacobian(type, X, slot);
}

CornerTargets::CornerTargets(const VolumeMesh& mesh, const UntangleOptions& options, const std::vector<char>& needed,
                             int threads) {
  if (!options.target) return;
  const int nc = mesh.num_cells();
  target_inverse_.resize(static_cast<size_t>(nc) * kCellSlots);
  auto target = [&](const Eigen::Matrix3d& W, const Eigen::Matrix3d& A, const Eigen::Matrix3d& ideal_inv) {
    const double eta = CornerEnergy{}(A, W.inverse());  // 1 where A has W's shape
    const double distortion = std::isfinite(eta) && eta > 0 ? std::clamp(1 - 1 / eta, 0.0, 1.0) : 1.0;
    return target_corner_inverse(W, ideal_inv, options.target_towards_ideal * distortion);
  };
#pragma omp parallel for num_threads(threads) schedule(dynamic, 256)
  for (int c = 0; c < nc; ++c) {
    if (!needed[c]) continue;
    const CellType type = mesh.types[c];
    const CellNodes Xt = cell_nodes(*options.target, c), X = cell_nodes(mesh, c);
    for (int k = 0; k < node_count(type); ++k)
      target_inverse_[c * kCellSlots + k] =
          target(corner_jacobian(type, Xt, k), corner_jacobian(type, X, k), ideal_corner_inverse(type, k));
    const auto& samples = interior_sample_weights(type);
    for (size_t s = 0; s < samples.size(); ++s)
      target_inverse_[c * kCellSlots + kSampleSlot + s] =
          target(Xt.transpose() * samples[s], X.transpose() * samples[s], Eigen::Matrix3d::Identity());
  }
}

const Eigen::Matrix3d& CornerTargets::inverse(const VolumeMesh& mesh, int cell, int slot) const {
  static const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();  // an interior sample's ideal Jacobian
  if (!target_inverse_.empty()) return target_inverse_[static_cast<size_t>(cell) * kCellSlots + slot];
  return slot >= kSampleSlot ? identity : ideal_corner_inverse(mesh.types[cell], slot);
}

}  // namespace facehex
