#include "core/baseline/thin_plate_spline.h"

#include <cblas.h>

#include <Eigen/LU>
#include <cmath>

#include "core/util/blas_threads.h"
#include "core/util/error.h"

namespace facehex {
namespace {

// [X 1], #X x 4.
Eigen::MatrixXd homogeneous(const Eigen::MatrixXd& X) {
  Eigen::MatrixXd H(X.rows(), 4);
  H << X, Eigen::VectorXd::Ones(X.rows());
  return H;
}

}  // namespace

ThinPlateSpline::ThinPlateSpline(const Eigen::MatrixXd& controls) {
  if (controls.rows() < 4 || controls.cols() != 3)
    throw Error("thin-plate spline", "needs at least 4 control points (#C x 3), got " +
                                         std::to_string(controls.rows()) + " x " + std::to_string(controls.cols()));
  center_ = controls.colwise().mean();
  scale_ = std::sqrt((controls.rowwise() - center_).rowwise().squaredNorm().mean());
  if (!(scale_ > 0)) throw Error("thin-plate spline", "the control points all coincide");
  controls_ = normalized(controls);
  W_ = Eigen::MatrixXd::Zero(controls.rows(), 3);
  A_ = Eigen::MatrixXd::Zero(4, 3);
  A_.topRows(3).setIdentity();
}

Eigen::MatrixXd ThinPlateSpline::normalized(const Eigen::MatrixXd& X) const { return (X.rowwise() - center_) / scale_; }

Eigen::MatrixXd ThinPlateSpline::kernel(const Eigen::MatrixXd& Xn) const {
  Eigen::MatrixXd K(Xn.rows(), controls_.rows());
  // A column per control point, from the coordinates' columns: contiguous, vectorized, no temporaries.
  const auto x = Xn.col(0).array(), y = Xn.col(1).array(), z = Xn.col(2).array();
  for (Eigen::Index i = 0; i < controls_.rows(); ++i)
    K.col(i) =
        -((x - controls_(i, 0)).square() + (y - controls_(i, 1)).square() + (z - controls_(i, 2)).square()).sqrt();
  return K;
}

void ThinPlateSpline::fit(const Eigen::MatrixXd& P, const Eigen::MatrixXd& Q, const Eigen::VectorXd& weight,
                          double stiffness) {
  const Eigen::Index n = controls_.rows(), m = P.rows();
  if (Q.rows() != m || weight.size() != m || P.cols() != 3 || Q.cols() != 3)
    throw Error("thin-plate spline", "sources, targets and weights differ in size");
  const Eigen::MatrixXd Pn = normalized(P), Qn = normalized(Q);
  // Weighted design matrix B = sqrt(weight) [Phi_pc, Pn 1], #M x (#C + 4).
  Eigen::MatrixXd B(m, n + 4);
  B << kernel(Pn), homogeneous(Pn);
  const Eigen::VectorXd root = weight.cwiseSqrt();
  B = root.asDiagonal() * B;
  // KKT system of: min |B theta - sqrt(weight) Qn|^2 + stiffness trace(W^T Phi_cc W)  s.t.  [C 1]^T W = 0.
  const Eigen::Index size = n + 8;
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(size, size);
  {
    // The lower triangle of B^T B by BLAS: OpenBLAS's kernels use the CPU's vector width, which Eigen's, compiled
    // for the baseline x86-64, do not. One thread, as for the factorizations (blas_threads.h).
    const SingleThreadedBlas one_thread;
    cblas_dsyrk(CblasColMajor, CblasLower, CblasTrans, static_cast<int>(n + 4), static_cast<int>(m), 1.0, B.data(),
                static_cast<int>(m), 0.0, H.data(), static_cast<int>(size));
  }
  H.topLeftCorner(n + 4, n + 4) = H.topLeftCorner(n + 4, n + 4).selfadjointView<Eigen::Lower>();
  H.topLeftCorner(n, n) += stiffness * kernel(controls_);
  const Eigen::MatrixXd Pc = homogeneous(controls_);
  H.block(n + 4, 0, 4, n) = Pc.transpose();
  H.block(0, n + 4, n, 4) = Pc;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(size, 3);
  rhs.topRows(n + 4) = B.transpose() * (root.asDiagonal() * Qn);
  // Singular only without stiffness and with too few or coplanar pairs: a pivot of the LU at round-off level says so.
  // (Well-posed fits without stiffness can be ill-conditioned, the normal equations square the condition number:
  // interpolating #C pairs at the controls gives pivot ratios about 1e-13.)
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(H);
  const Eigen::VectorXd pivots = lu.matrixLU().diagonal().cwiseAbs();
  if (!(pivots.minCoeff() > 1e-15 * pivots.maxCoeff()))
    throw Error("thin-plate spline", "singular system: too few or coplanar pairs (" + std::to_string(m) + " pairs)");
  const Eigen::MatrixXd theta = lu.solve(rhs);
  W_ = theta.topRows(n);
  A_ = theta.middleRows(n, 4);
}

Eigen::MatrixXd ThinPlateSpline::operator()(const Eigen::MatrixXd& X) const {
  const Eigen::MatrixXd Xn = normalized(X);
  const Eigen::MatrixXd Yn = kernel(Xn) * W_ + homogeneous(Xn) * A_;
  return (Yn * scale_).rowwise() + center_;
}

}  // namespace facehex
