#pragma once
// Untangling and local smoothing of a hex-dominant mesh (the "never an inverted element" guarantee).
//
// Energy (Escobar et al., simultaneous untangling and smoothing): per corner k of a cell, with A_k the corner matrix
// (corner_jacobian.h) and W_k the same corner of the ideal cell, S = A_k W_k^-1, sigma = det S,
//     eta = |S|_F^2 / (3 h(sigma)^(2/3)),   h(sigma) = (sigma + sqrt(sigma^2 + 4 delta^2)) / 2.
// eta is the inverse mean-ratio shape of the corner (1 for the ideal corner, larger when distorted); with delta > 0,
// h stays positive for inverted corners, so the sum is finite and smooth and its minimum has sigma > 0 everywhere:
// minimizing it untangles. delta is taken from the worst corner and shrinks to 0 once nothing is inverted.
//
// Only vertices near bad cells move (within `rings` vertex rings of a cell that is inverted or whose scaled Jacobian
// is below `min_scaled_jacobian`), so the rest of the mapped mesh keeps exactly the shape the mapping gave it.
// Each vertex has a motion constraint: fixed (on the patient's surface), sliding in a plane (on a feature surface
// such as the mid-sagittal sheet: it moves in the feature's tangent plane), or free. Each sweep visits the movable
// vertices in order and moves each along its (projected) energy gradient with a backtracking line search (local
// Gauss-Seidel descent).
#include "core/mesh.h"

#include <Eigen/Core>
#include <vector>

namespace facehex {

struct UntangleOptions {
  double min_scaled_jacobian = 0.2;  // cells below this count as bad, besides inverted ones
  int rings = 2;
  int max_sweeps = 100;
};

struct UntangleReport {
  int inverted_before = 0, inverted_after = 0;
  int bad_before = 0, bad_after = 0;  // inverted or below min_scaled_jacobian
  double min_scaled_jacobian_before = 0, min_scaled_jacobian_after = 0;
  int free_vertices = 0;  // vertices allowed to move
  int sweeps = 0;
};

// How each vertex may move: P (3 x 3) projects a displacement onto the allowed directions: zero = fixed, identity =
// free, I - n n^T = sliding in the plane of normal n.
using MotionConstraints = std::vector<Eigen::Matrix3d>;
MotionConstraints fixed_or_free(const std::vector<char>& fixed);

// mesh: modified in place (V only). motion: #V projections.
UntangleReport untangle(VolumeMesh& mesh, const MotionConstraints& motion, const UntangleOptions& options = {});

}  // namespace facehex
