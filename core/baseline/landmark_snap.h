#pragma once
// A smooth, local displacement that carries points exactly onto their targets (the landmarks a registration pulls
// only in the least-squares sense, mesh_matching.h):
//
//   d(x) = sum_i w_i phi(|x - a_i| / radius),   phi(r) = (1 - r)^4 (4 r + 1) for r < 1, else 0,
//
// Wendland's compactly supported C2 function, positive definite in 3D: for distinct points a_i (#L x 3) the weights
// w_i (#L x 3) with d(a_j) = b_j - a_j exist and are unique. Points farther than `radius` from every a_i do not move.
// The displacement's gradient grows with |b - a| / radius: a radius several times the largest residual keeps the
// displaced surface as smooth as it was.
#include <Eigen/Core>

namespace facehex {

// X #X x 3 points; from, to #L x 3. Returns X + d(X). Throws facehex::Error("landmark snap", ...) if two points of
// `from` closer than 1e-6 * radius are sent to different targets, or radius <= 0 with landmarks given.
Eigen::MatrixXd landmark_snap(const Eigen::MatrixXd& X, const Eigen::MatrixXd& from, const Eigen::MatrixXd& to,
                              double radius);

}  // namespace facehex
