#pragma once
// How the shape solvers move vertices: through parameters p, with a placement function giving the position x(p) and
// dx/dp. With p = x this is plain smoothing in space; with p = (u, v, w) and x = the patient's inverse
// parameterization (core/mapping/hex_transfer.h), a vertex whose u is pinned keeps exactly that u: it stays on the
// patient's side or feature surface.
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "core/mesh/mesh.h"

namespace facehex {

struct VertexPlacement {
  Eigen::MatrixXd p;                     // #V x 3 parameters of each vertex
  std::vector<Eigen::Matrix3d> movable;  // #V projections onto the parameter directions that may change (0: fixed)
  // Position x and dx/dp of vertex v at parameters q; false when q is not admissible.
  std::function<bool(int v, const Eigen::Vector3d& q, Eigen::Vector3d& x, Eigen::Matrix3d& dxdq)> place;
};

// p = x: vertices move freely in space, except the fixed ones (#V flags, nonzero = fixed).
VertexPlacement spatial_placement(const Eigen::MatrixXd& V, const std::vector<char>& fixed);

}  // namespace facehex
