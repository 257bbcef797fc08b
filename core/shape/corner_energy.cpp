#include "core/shape/corner_energy.h"

#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

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

// What both evaluations need of S: s^2 = |S|_F^2 / 3 (f) and its powers, det S, sigma, and the energy phi(sigma) =
// h(sigma)^-q (q = 2 power / 3) with, if `derivatives`, its first two derivatives by sigma (the line search asks for
// the energy alone); empty where the energy is infinite.
struct SigmaTerms {
  double f, f32, d, sigma, energy, dphi = 0, d2phi = 0;
};

// h^(-2 power / 3): by a cube root and multiplications for the small whole powers the solvers use (the relaxation's
// 1, the template repair's 8), cheaper than std::pow; std::pow otherwise.
double inverse_power_two_thirds(double h, double power) {
  constexpr double kLargestWholePower = 16;
  if (!(power >= 1 && power <= kLargestWholePower && power == std::floor(power)))
    return std::pow(h, -2.0 * power / 3.0);
  const int whole = static_cast<int>(power);
  const double root = std::cbrt(h);
  const double base = 1.0 / (root * root);
  double result = base;
  for (int i = 1; i < whole; ++i) result *= base;
  return result;
}

std::optional<SigmaTerms> sigma_terms(const Eigen::Matrix3d& S, double delta2, double power, bool derivatives) {
  SigmaTerms t;
  t.f = S.squaredNorm() / 3;
  if (!(t.f > 0)) return std::nullopt;
  t.f32 = t.f * std::sqrt(t.f);
  t.d = S.determinant();
  t.sigma = t.d / t.f32;
  const double root = std::sqrt(t.sigma * t.sigma + 4 * delta2);
  const double h = 0.5 * (t.sigma + root);
  if (!(h > 0)) return std::nullopt;
  const double q = 2.0 * power / 3.0;
  t.energy = inverse_power_two_thirds(h, power);
  if (!derivatives) return t;
  const double dh = 0.5 * (1 + t.sigma / root), d2h = 2 * delta2 / (root * root * root);
  t.dphi = -q * t.energy / h * dh;
  t.d2phi = q * (q + 1) * t.energy / (h * h) * dh * dh - q * t.energy / h * d2h;
  return t;
}

}  // namespace

double CornerEnergy::operator()(const Eigen::Matrix3d& A, const Eigen::Matrix3d& Winv,
                                Eigen::Matrix3d* gradient) const {
  const Eigen::Matrix3d S = A * Winv;
  const std::optional<SigmaTerms> t = sigma_terms(S, delta2, power, gradient != nullptr);
  if (!t) return std::numeric_limits<double>::infinity();
  if (gradient) *gradient = t->dphi * (cofactor(S) / t->f32 - t->sigma * S / t->f) * Winv.transpose();
  return t->energy;
}

double CornerEnergy::node(const Eigen::Matrix3d& A, const Eigen::Matrix3d& Winv, const Eigen::Vector3d& coefficient,
                          Eigen::Vector3d& gradient, Eigen::Matrix3d& hessian) const {
  const Eigen::Matrix3d S = A * Winv;
  const std::optional<SigmaTerms> t = sigma_terms(S, delta2, power, true);
  if (!t) return std::numeric_limits<double>::infinity();
  const double f52 = t->f32 * t->f, f72 = f52 * t->f;
  // S moves with the node as S + x w^T, w = Winv^T c: |S|^2 is quadratic in x and det S linear (a rank-one update).
  const Eigen::Vector3d w = Winv.transpose() * coefficient;
  const Eigen::Vector3d df = (2.0 / 3.0) * S * w;
  const Eigen::Vector3d dd = cofactor(S) * w;
  const Eigen::Vector3d dsigma = dd / t->f32 - 1.5 * t->d / f52 * df;
  Eigen::Matrix3d d2sigma =
      -1.5 / f52 * (dd * df.transpose() + df * dd.transpose()) + 3.75 * t->d / f72 * df * df.transpose();
  d2sigma.diagonal().array() -= t->d / f52 * w.squaredNorm();
  gradient = t->dphi * dsigma;
  hessian = t->d2phi * dsigma * dsigma.transpose() + t->dphi * d2sigma;
  return t->energy;
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
