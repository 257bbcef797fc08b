#pragma once
// The shape energy of one cell corner, measured against a target corner (after Escobar et al., simultaneous
// untangling and smoothing), with its gradient and Hessian.
//
// For a corner matrix A (corner_jacobian.h: the three edge vectors leaving the corner node, as columns, or the
// Jacobian at an interior sample) and a target corner W, S = A W^-1, its normalized determinant
//     sigma = det S / s^3,  s^2 = |S|_F^2 / 3,   in [-1, 1], 1 only when A has W's shape (any size, any rotation),
// and
//     eta = h(sigma)^(-2/3),   h(sigma) = (sigma + sqrt(sigma^2 + 4 delta^2)) / 2,   energy = eta^power.
// With delta = 0, eta = |S|_F^2 / (3 det(S)^(2/3)), the inverse mean-ratio shape of the corner (1 at W's shape,
// infinite when flat: a barrier against inversion); with delta > 0, h stays positive for inverted corners, so a sum
// over corners is finite and smooth and its minimum has sigma > 0: minimizing it untangles. Normalizing sigma makes
// delta mean the same for small and large cells.
//
#include <Eigen/Core>

#include "core/mesh/mesh.h"

namespace facehex {

// sigma of S: det S / (|S|_F^2 / 3)^(3/2), in [-1, 1].
double normalized_determinant(const Eigen::Matrix3d& S);

struct CornerEnergy {
  double delta2 = 0;  // delta^2, dimensionless
  double power = 1;

  // The energy of corner A against target W (given as W^-1); infinite for a collapsed corner (S = 0) or, with
  // delta = 0, a flat or inverted one.
  double operator()(const Eigen::Matrix3d& A, const Eigen::Matrix3d& Winv) const;

  // The energy and its gradient and Hessian by the position x of one node of the corner, where A = A_0 + x c^T
  // (c = `coefficient`: the node's column pattern in a corner matrix, corner_jacobian.h, or its weights at an
  // interior sample). Exact: det A is linear and |A|^2 quadratic in x. Gradient and Hessian mean nothing when the
  // energy is infinite.
  double node(const Eigen::Matrix3d& A, const Eigen::Matrix3d& Winv, const Eigen::Vector3d& coefficient,
              Eigen::Vector3d& gradient, Eigen::Matrix3d& hessian) const;

  // The same summed over n corners that move with one node, each given as S_i = A_i W_i^-1 and, for the derivatives,
  // w_i = W_i^-T c_i (S_i moves as S_i + x w_i^T). One loop over plain arrays: the corners' square roots, cube roots
  // and divisions, which bound the work, overlap from one corner to the next.
  double sum(const Eigen::Matrix3d* S, int n) const;
  double sum(const Eigen::Matrix3d* S, const Eigen::Vector3d* w, int n, Eigen::Vector3d& gradient,
             Eigen::Matrix3d& hessian) const;
};

// W_k^-1 of the ideal cell's corner k (k < node_count(type); ideal_cell in corner_jacobian.h).
const Eigen::Matrix3d& ideal_corner_inverse(CellType type, int k);

// W^-1 for a target corner W whose ideal counterpart has inverse ideal_inv, with W's stretch moved `towards_ideal`
// of the way (0: W's shape, 1: the ideal's) to the ideal corner's; W's rotation does not matter (the energy does not
// change when S is rotated from the right). A nearly flat or inverted W gives the ideal corner.
Eigen::Matrix3d target_corner_inverse(const Eigen::Matrix3d& W, const Eigen::Matrix3d& ideal_inv, double towards_ideal);

}  // namespace facehex
