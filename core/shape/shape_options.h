#pragma once
// The settings and the report of the shape solver (core/shape/untangle.h, on the energy of corner_energy.h): which
// cells count as bad (cell_bounds.h), which vertices may move, the target shapes and the energy's weighting.
#include <Eigen/Core>

#include "core/mesh/mesh.h"
#include "core/util/progress.h"

namespace facehex {

struct UntangleOptions {
  double min_scaled_jacobian = 0.2;  // cells below this count as bad, besides inverted ones
  // Optional, #C: each cell's scaled Jacobian in the mesh it was mapped from. A cell counts as bad only below
  // min(min_scaled_jacobian, half of it): a cell that was already that poor in the standard is kept as the standard
  // has it (improving it would change the standard's shape, which the transfer is meant to keep).
  Eigen::VectorXd reference_scaled_jacobian;
  // Grow the region that may move from the unusable cells only (inverted or flat), not from every bad cell: for
  // passes that finish the untangling of what an earlier pass left.
  bool seed_unusable_only = false;
  // Optional: a mesh with the same cells (the standard this mesh was mapped from) whose cells give each corner's
  // target shape: W_k is that cell's corner k (and each interior sample's target its Jacobian there) instead of the
  // ideal cell's, so the energy measures how far each corner is from the target's shape, whatever its size and
  // rotation (dihedral angles are what it keeps). Target corners that are nearly flat (normalized determinant below
  // 0.1) or inverted use the ideal cell's.
  const VolumeMesh* target = nullptr;
  // Each target corner's shape is moved towards the ideal corner's by target_towards_ideal * d, with d = 1 - 1/eta
  // in [0, 1) the corner's distortion against the target in the mesh as given (0 where it has the target's shape).
  // Where the mesh already has the target's shape it is kept exactly (mapping a standard onto itself stays the
  // identity); where it was forced far from it (a patient unlike the standard), the aim is a better-shaped corner
  // rather than a copy of a poor one.
  double target_towards_ideal = 0;
  // Optional, #V x 3: where each vertex should stay (the mapping's result, whose positions carry the correspondence).
  // The energy adds tether_weight * |x - tether|^2 / h^2 per vertex, h its mean edge length in the mesh as given: a
  // relaxation that slides a vertex one edge along the skin for a better shape pays tether_weight for it, so shape
  // and correspondence are traded by one number (0: no tether).
  Eigen::MatrixXd tether;
  double tether_weight = 0;
  // Every movable vertex may move, not only those near bad cells (shape relaxation of the whole mesh).
  bool whole_mesh = false;
  int rings = 2;
  int max_sweeps = 60;
  // The sweeps also stop once one lowers the energy by less than this share of what all of them together have
  // lowered it by (0: never): a whole-mesh smoothing's long tail moves every vertex a little every sweep and changes
  // the shapes by little (relaxation_options).
  double settled_energy_share = 0;
  // The line search starts from this multiple of the Newton step, then halves (successive over-relaxation): long,
  // smooth moves, which Gauss-Seidel sweeps propagate slowly, need fewer sweeps. A repair keeps 1, since longer steps
  // can leave a fold inverted that plain steps untangle (relaxation_options sets the relaxation's).
  double over_relaxation = 1;
  // If > 0, a step never brings a cell whose scaled Jacobian is at or above this below it (relaxation_options).
  double keep_above = 0;
  // The energy sums eta^corner_power over the corners: above 1 the worst corners weigh more (towards maximizing the
  // minimum quality, which the sum of eta only does loosely). The template's repair uses 8 (template_mesh.h); the
  // transfer's repair keeps 1: a higher power trades the many fair cells, and the standard's angles, for the few
  // worst ones, which costs the transfer more than it gains.
  double corner_power = 1;
  // Threads for the sweeps; 0: as many as there are idle cores (idle_cores.h), up to OpenMP's maximum. The result is
  // the same for every thread count.
  int threads = 0;
  // Called after each sweep with stage "untangling" and the fraction of max_sweeps done; returning false cancels
  // (Cancelled is thrown between sweeps).
  ProgressCallback progress;
};

// The shape relaxation's settings, from a repair's (`repair`: its bounds, targets, threads): every movable vertex
// moves, for at most 40 sweeps and until a sweep lowers the energy by less than a thousandth of what the sweeps
// before it did (whatever folds are left, which the repair then takes on); steps start at 1.8 times the Newton step
// (long, smooth moves go further per sweep, so the budget reaches the shapes that plain steps reach in more sweeps:
// docs/benchmarks.md); no good cell drops below a scaled Jacobian of 0.05 (while folds remain, the energy's
// regularization weakens its barrier against flat corners, so a cell far from any fold could otherwise come out nearly
// flat); the plain sum of the corners' energies (the relaxation evens out all cells; a higher power is for a repair's
// worst ones).
UntangleOptions relaxation_options(UntangleOptions repair);

struct UntangleReport {
  int inverted_before = 0, inverted_after = 0;
  int degenerate_before = 0, degenerate_after = 0;  // flat, not inverted (corner_jacobian.h)
  int bad_before = 0, bad_after = 0;                // inverted or below their bound (UntangleOptions)
  double min_scaled_jacobian_before = 0, min_scaled_jacobian_after = 0;
  int free_vertices = 0;  // vertices allowed to move
  int sweeps = 0;
  long vertex_steps = 0;  // Newton steps taken over all sweeps (a vertex is stepped in a sweep only if awake)
  bool settled = false;   // the sweeps stopped on settled_energy_share, before max_sweeps
  // Passes stopped because their unusable cells had not become fewer for a while (untangle.h): what the report's
  // counts after them say is left is what those passes could not untangle.
  int stalled_passes = 0;
  int released_feature_vertices = 0;  // feature pins released to untangle the last folds (transfer_pipeline)
  int released_side_vertices = 0;     // vertices moved in space, off exact sides, to untangle what remained
};

}  // namespace facehex
