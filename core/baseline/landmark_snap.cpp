#include "core/baseline/landmark_snap.h"

#include <Eigen/Dense>
#include <cmath>

#include "core/util/error.h"

namespace facehex {
namespace {

double wendland_c2(double r) {
  if (r >= 1) return 0;
  const double s = 1 - r;
  return s * s * s * s * (4 * r + 1);
}

}  // namespace

Eigen::MatrixXd landmark_snap(const Eigen::MatrixXd& X, const Eigen::MatrixXd& from, const Eigen::MatrixXd& to,
                              double radius) {
  const Eigen::Index n = from.rows();
  if (n == 0) return X;
  if (!(radius > 0)) throw Error("landmark snap", "the support radius must be positive");
  if (to.rows() != n || from.cols() != 3 || to.cols() != 3 || X.cols() != 3)
    throw Error("landmark snap", "the landmarks are not two lists of the same number of 3D points");
  // Points that coincide with the same target are one condition, not a singular system.
  Eigen::MatrixXd a(0, 3), b(0, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    bool repeated = false;
    for (Eigen::Index j = 0; j < a.rows() && !repeated; ++j) {
      if ((a.row(j) - from.row(i)).norm() >= 1e-6 * radius) continue;
      if ((b.row(j) - to.row(i)).norm() >= 1e-6 * radius)
        throw Error("landmark snap", "two landmarks at the same point are sent to different places");
      repeated = true;
    }
    if (repeated) continue;
    a.conservativeResize(a.rows() + 1, 3);
    b.conservativeResize(b.rows() + 1, 3);
    a.row(a.rows() - 1) = from.row(i);
    b.row(b.rows() - 1) = to.row(i);
  }
  const Eigen::Index m = a.rows();
  Eigen::MatrixXd Phi(m, m);
  for (Eigen::Index i = 0; i < m; ++i)
    for (Eigen::Index j = 0; j < m; ++j) Phi(i, j) = wendland_c2((a.row(i) - a.row(j)).norm() / radius);
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(Phi);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive())
    throw Error("landmark snap", "the landmarks' interpolation system is singular");
  const Eigen::MatrixXd w = ldlt.solve(b - a);
  Eigen::MatrixXd Y = X;
  for (Eigen::Index k = 0; k < X.rows(); ++k)
    for (Eigen::Index i = 0; i < m; ++i) {
      const double phi = wendland_c2((X.row(k) - a.row(i)).norm() / radius);
      if (phi > 0) Y.row(k) += phi * w.row(i);
    }
  return Y;
}

}  // namespace facehex
