#pragma once
// Untangling and local smoothing of a hex-dominant mesh (the "never an inverted element" guarantee).
//
// Energy (after Escobar et al., simultaneous untangling and smoothing): per corner k of a cell, with A_k the corner
// matrix (corner_jacobian.h) and W_k the same corner of the ideal cell, S = A_k W_k^-1, its normalized determinant
// sigma = det S / (|S|_F^2 / 3)^(3/2) in [-1, 1], and
//     eta = h(sigma)^(-2/3),   h(sigma) = (sigma + sqrt(sigma^2 + 4 delta^2)) / 2.
// With delta = 0, eta = |S|_F^2 / (3 det(S)^(2/3)), the inverse mean-ratio shape of the corner (1 for the ideal
// corner, larger when distorted); with delta > 0, h stays positive for inverted corners, so the sum is finite and
// smooth and its minimum has sigma > 0 everywhere: minimizing it untangles. Normalizing sigma makes delta mean the
// same for small and large cells. delta is taken from the worst corner and is 0 once nothing is inverted. A hex's
// centre counts as a corner too, with S = its Jacobian. A step is taken only if it makes no cell around the vertex
// unusable (inverted at a corner or an interior sample point, corner_jacobian.h, or flat), so the result is valid
// where solvers evaluate it.
//
// Only vertices near bad cells move (within `rings` vertex rings of a cell that is inverted or whose scaled Jacobian
// is below `min_scaled_jacobian`, or below half its scaled Jacobian in the standard when that is lower); a step never
// makes a cell unusable (inverted or degenerate) that was not, so the rest of the mapped mesh keeps exactly the shape
// the mapping gave it. Vertices move through parameters: the untangler changes a vertex's parameters p, and a placement
// function gives its position x(p) and dx/dp. With p = x this is plain smoothing in space; with p = (u, v, w) and x =
// the patient's inverse parameterization (hex_transfer.h), a vertex whose u is pinned (a shape end, or the mid-sagittal
// feature) keeps exactly that u: it stays exactly on the patient's side or feature surface, and every vertex stays
// inside the patient. Each sweep visits the movable vertices and takes a Newton step (finite-difference Hessian) in the
// movable parameter directions with a backtracking line search (local Gauss-Seidel descent).
#include <Eigen/Core>
#include <functional>
#include <vector>

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
  // Every movable vertex may move, not only those near bad cells (shape relaxation of the whole mesh).
  bool whole_mesh = false;
  int rings = 2;
  int max_sweeps = 60;
  // A vertex's Newton step uses a finite-difference Hessian of its energy (3 of the step's 4 gradient evaluations);
  // it is recomputed every this many sweeps and reused in between (the line search keeps every step a descent):
  // between sweeps a vertex's neighbourhood changes little, so a reused Hessian still gives good steps at a fraction
  // of the cost, and the results stay close to those of a fresh Hessian per step.
  int hessian_every_sweeps = 3;
  // The line search starts from this multiple of the Newton step, then halves (successive over-relaxation): long,
  // smooth moves, which Gauss-Seidel sweeps propagate slowly, need fewer sweeps. The transfer's shape relaxation uses
  // 1.5 (a lower energy within its sweep budget); the repair keeps 1, since longer steps can leave a fold inverted
  // that plain steps untangle.
  double over_relaxation = 1;
  // If > 0, a step never brings a cell whose scaled Jacobian is at or above this below it. The transfer's shape
  // relaxation uses 0.05: while folds remain, the energy's regularization weakens its barrier against flat corners,
  // so without this bound a cell far from any fold could come out nearly flat.
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

struct UntangleReport {
  int inverted_before = 0, inverted_after = 0;
  int degenerate_before = 0, degenerate_after = 0;  // flat, not inverted (corner_jacobian.h)
  int bad_before = 0, bad_after = 0;                // inverted or below their bound (UntangleOptions)
  double min_scaled_jacobian_before = 0, min_scaled_jacobian_after = 0;
  int free_vertices = 0;  // vertices allowed to move
  int sweeps = 0;
  int released_feature_vertices = 0;  // feature pins released to untangle the last folds (transfer_pipeline)
  int released_side_vertices = 0;     // vertices moved in space, off exact sides, to untangle what remained
};

struct VertexPlacement {
  Eigen::MatrixXd p;                     // #V x 3 parameters of each vertex
  std::vector<Eigen::Matrix3d> movable;  // #V projections onto the parameter directions that may change (0: fixed)
  // Position x and dx/dp of vertex v at parameters q; false when q is not admissible.
  std::function<bool(int v, const Eigen::Vector3d& q, Eigen::Vector3d& x, Eigen::Matrix3d& dxdq)> place;
};

// The vertices `marked` (#V flags) and those sharing a cell with them, grown `rings` times: the neighbourhood of a
// set of vertices in cell rings.
std::vector<char> within_cell_rings(const VolumeMesh& mesh, std::vector<char> marked, int rings);

// p = x: vertices move freely in space, except the fixed ones (#V flags, nonzero = fixed).
VertexPlacement spatial_placement(const Eigen::MatrixXd& V, const std::vector<char>& fixed);

// mesh: modified in place (V only); placement.p follows the moves.
UntangleReport untangle(VolumeMesh& mesh, VertexPlacement& placement, const UntangleOptions& options = {});

}  // namespace facehex
