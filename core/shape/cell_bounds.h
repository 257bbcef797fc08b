#pragma once
// Which cells the shape solvers count as bad, and the counts their reports give (shape_options.h).
#include <Eigen/Core>

#include "core/mesh/mesh.h"
#include "core/shape/shape_options.h"

namespace facehex {

class CellBounds {
 public:
  // Throws if options.reference_scaled_jacobian or options.target does not match the mesh's cells.
  CellBounds(const VolumeMesh& mesh, const UntangleOptions& options);

  // The scaled Jacobian below which cell c counts as bad: min_scaled_jacobian, or half the cell's scaled Jacobian in
  // the mesh it was mapped from when that is lower.
  double bound(int c) const;
  // Inverted, or below its bound.
  bool is_bad(const VolumeMesh& mesh, int c) const;

  struct Counts {
    int inverted = 0, degenerate = 0, bad = 0;
    double min_scaled_jacobian = 1;
  };
  Counts count(const VolumeMesh& mesh) const;

 private:
  const UntangleOptions& options_;
};

// Slot of a cell's corner k (k < 8) or interior sample s (kSampleSlot + s) in per-cell tables.
constexpr int kSampleSlot = 8;
constexpr int kCellSlots = kSampleSlot + 9;

// W^-1 of each corner and interior sample of the cells flagged in `needed` (#C): the ideal cell's, or with
// options.target the target's moved towards the ideal by options.target_towards_ideal times the corner's distortion
// in `mesh` as given (shape_options.h). Computed on `threads` threads.
class CornerTargets {
 public:
  CornerTargets(const VolumeMesh& mesh, const UntangleOptions& options, const std::vector<char>& needed, int threads);
  const Eigen::Matrix3d& inverse(const VolumeMesh& mesh, int cell, int slot) const;

 private:
  std::vector<Eigen::Matrix3d> target_inverse_;  // #C x kCellSlots, with a target only
};

// A cell's corner matrix (corner_jacobian.h) at `slot`: the corner's edge matrix or the interior sample's Jacobian.
Eigen::Matrix3d slot_matrix(CellType type, const Eigen::Matrix<double, 8, 3>& X, int slot);

}  // namespace facehex
