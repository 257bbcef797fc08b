#include "core/shape/corner_energy.h"

#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <limits>

#include "core/mesh/corner_jacobian.h"

namespace facehex {
namespace {

constexpr double kNearlyFlatTarget = 0.1;  // target corners below this normalized determinant use the ideal corner

// d det(S) / d S
Eigen::Matrix3d cofactor(const Eigen::Matrix3d& S) {
  Eigen::Matrix3d cof;
  cof.col(0) = S.col(1).cross(S.col(2));
  cof.col(1) = S.col(2).cross(S.col(0));
  cof.col(2) = S.col(0).cross(S.col(1));
  return cof;
}

}  // namespace

double normalized_determinant(const Eigen::Matrix3d& S) {
  const double s2 = S.squaredNorm() / 3;
  return S.determinant() / (s2 * std::sqrt(s2));
}

namespace {

// h^(-2 power / 3): by a cube root and multiplications for the small whole powers the solvers use (the relaxation's
// 1, the template repair's 8), cheaper than std::pow; std::pow otherwise.
class InversePowerTwoThirds {
 public:
  explicit InversePowerTwoThirds(double power) : power_(power) {
    constexpr double kLargestWholePower = 16;
    whole_ = power >= 1 && power <= kLargestWholePower && power == std::floor(power) ? static_cast<int>(power) : 0;
  }
  double operator()(double h) const {
    if (whole_ == 0) return std::pow(h, -2.0 * power_ / 3.0);
    const double root = std::cbrt(h);
    const double base = 1.0 / (root * root);
    double result = base;
    for (int i = 1; i < whole_; ++i) result *= base;
    return result;
  }

 private:
  double power_;
  int whole_;
};

double finite_or_infinity(double total) {
  return std::isfinite(total) ? total : std::numeric_limits<double>::infinity();
}

}  // namespace

// A collapsed corner (f = 0) gives sigma = NaN, a flat or inverted one without regularization h = 0: either makes
// the sum NaN or infinite, which is returned as infinity.
double CornerEnergy::sum(const Eigen::Matrix3d* S, int n) const {
  const InversePowerTwoThirds phi(power);
  double total = 0;
  for (int i = 0; i < n; ++i) {
    const double f = S[i].squaredNorm() / 3;
    const double sigma = S[i].determinant() / (f * std::sqrt(f));
    total += phi(0.5 * (sigma + std::sqrt(sigma * sigma + 4 * delta2)));
  }
  return finite_or_infinity(total);
}

// With f = |S|^2 / 3, d = det S, sigma = d / f^(3/2) and phi(sigma) = h(sigma)^-q (q = 2 power / 3): S moves with the
// node as S + x w^T, so df/dx = (2/3) S w and dd/dx = cof(S) w (det S is linear in x); the chain rule through sigma
// gives the gradient phi' dsigma and the Hessian phi'' dsigma dsigma^T + phi' d2sigma.
double CornerEnergy::sum(const Eigen::Matrix3d* S, const Eigen::Vector3d* w, int n, Eigen::Vector3d& gradient,
                         Eigen::Matrix3d& hessian) const {
  const InversePowerTwoThirds phi(power);
  const double q = 2.0 * power / 3.0;
  double total = 0;
  gradient.setZero();
  hessian.setZero();
  for (int i = 0; i < n; ++i) {
    const double f = S[i].squaredNorm() / 3, f32 = f * std::sqrt(f), f52 = f32 * f, f72 = f52 * f;
    const double d = S[i].determinant(), sigma = d / f32;
    const double root = std::sqrt(sigma * sigma + 4 * delta2);
    const double h = 0.5 * (sigma + root);
    const double energy = phi(h);
    const double dh = 0.5 * (1 + sigma / root), d2h = 2 * delta2 / (root * root * root);
    const double dphi = -q * energy / h * dh;
    const double d2phi = q * (q + 1) * energy / (h * h) * dh * dh - q * energy / h * d2h;
    const Eigen::Vector3d df = (2.0 / 3.0) * S[i] * w[i];
    const Eigen::Vector3d dd = cofactor(S[i]) * w[i];
    const Eigen::Vector3d dsigma = dd / f32 - 1.5 * d / f52 * df;
    Eigen::Matrix3d d2sigma =
        -1.5 / f52 * (dd * df.transpose() + df * dd.transpose()) + 3.75 * d / f72 * df * df.transpose();
    d2sigma.diagonal().array() -= d / f52 * w[i].squaredNorm();
    total += energy;
    gradient += dphi * dsigma;
    hessian += d2phi * dsigma * dsigma.transpose() + dphi * d2sigma;
  }
  return finite_or_infinity(total);
}

double CornerEnergy::operator()(const Eigen::Matrix3d& A, const Eigen::Matrix3d& Winv) const {
  const Eigen::Matrix3d S = A * Winv;
  return sum(&S, 1);
}

double CornerEnergy::node(const Eigen::Matrix3d& A, const Eigen::Matrix3d& Winv, const Eigen::Vector3d& coefficient,
                          Eigen::Vector3d& gradient, Eigen::Matrix3d& hessian) const {
  const Eigen::Matrix3d S = A * Winv;
  const Eigen::Vector3d w = Winv.transpose() * coefficient;
  return sum(&S, &w, 1, gradient, hessian);
}

const Eigen::Matrix3d& ideal_corner_inverse(CellType type, int k) {
  static const auto table = [] {
    std::array<std::array<Eigen::Matrix3d, 8>, 3> t;
    const CellType types[3] = {CellType::Tet, CellType::Wedge, CellType::Hex};
    for (int i = 0; i < 3; ++i) {
      const CellNodes X = ideal_cell(types[i]);
      for (int c = 0; c < node_count(types[i]); ++c) t[i][c] = corner_jacobian(types[i], X, c).inverse();
    }
    return t;
  }();
  return table[type == CellType::Tet ? 0 : type == CellType::Wedge ? 1 : 2][k];
}

// With M = W ideal_inv (the target relative to the ideal corner) and its polar decomposition M = R U, the stretch U
// is scaled to unit determinant and moved towards the identity; R is dropped.
Eigen::Matrix3d target_corner_inverse(const Eigen::Matrix3d& W, const Eigen::Matrix3d& ideal_inv,
                                      double towards_ideal) {
  const Eigen::Matrix3d M = W * ideal_inv;
  if (!(normalized_determinant(M) > kNearlyFlatTarget)) return ideal_inv;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(M.transpose() * M);
  Eigen::Vector3d stretch = eigen.eigenvalues().cwiseMax(0).cwiseSqrt();
  stretch /= std::cbrt(stretch.prod());
  const Eigen::Vector3d blended = (1 - towards_ideal) * stretch.array() + towards_ideal;
  return ideal_inv * eigen.eigenvectors() * blended.cwiseInverse().asDiagonal() * eigen.eigenvectors().transpose();
}

}  // namespace facehex
