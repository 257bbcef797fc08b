#pragma once
// A smoothing thin-plate spline in 3D, the non-rigid part of the mesh-matching baseline (mesh_matching.h):
//
//   f(x) = A x + b + sum_i w_i phi(|x - c_i|),   phi(r) = -r (the biharmonic kernel in 3D),
//
// with fixed control points c_i (#C x 3) and sum_i w_i = 0, sum_i w_i c_i^T = 0, so that the bending energy
// E_bend = trace(W^T Phi_cc W) (Phi_cc #C x #C, W #C x 3) is >= 0 and zero exactly for affine maps. Fitting minimizes
//
//   sum_j weight_j |f(p_j) - q_j|^2  +  stiffness * E_bend
//
// over pairs (p_j -> q_j), both terms in coordinates centred on the controls and scaled by their RMS radius (so the
// stiffness is unitless and the same value means the same smoothness on a small or a large model): a large stiffness
// gives the best affine map, a small one bends to follow the pairs.
#include <Eigen/Core>

namespace facehex {

class ThinPlateSpline {
 public:
  explicit ThinPlateSpline(const Eigen::MatrixXd& controls);  // #C x 3, #C >= 4 not all on one plane

  // P, Q #M x 3 source and target points, weight #M (>= 0, summing to 1). Throws facehex::Error("thin-plate spline",
  // ...) if the system is singular (e.g. fewer than 4 affinely independent pairs and stiffness 0).
  void fit(const Eigen::MatrixXd& P, const Eigen::MatrixXd& Q, const Eigen::VectorXd& weight, double stiffness);

  Eigen::MatrixXd operator()(const Eigen::MatrixXd& X) const;  // #X x 3 -> #X x 3; the identity before fit()

 private:
  Eigen::MatrixXd kernel(const Eigen::MatrixXd& Xn) const;  // #X x #C, Xn normalized
  Eigen::MatrixXd normalized(const Eigen::MatrixXd& X) const;

  Eigen::MatrixXd controls_;  // #C x 3, normalized
  Eigen::RowVector3d center_;
  double scale_ = 1;
  Eigen::MatrixXd W_;  // #C x 3 kernel weights (normalized units)
  Eigen::MatrixXd A_;  // 4 x 3: rows x, y, z, 1 (normalized units)
};

}  // namespace facehex
