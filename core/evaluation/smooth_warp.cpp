#include "core/evaluation/smooth_warp.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

namespace facehex {
namespace {

const double kGradientPeak = std::exp(-0.5);  // max over r of (r / s^2) exp(-r^2 / (2 s^2)), times s

double gaussian(const GaussianBump& b, const Eigen::Vector3d& x) {
  return std::exp(-(x - b.centre).squaredNorm() / (2 * b.sigma * b.sigma));
}

// Uniform in [lo, hi) from the generator's raw 64 bits (std::uniform_real_distribution's result is not fixed by
// the standard).
double uniform(std::mt19937_64& rng, double lo, double hi) {
  const double unit = static_cast<double>(rng() >> 11) * 0x1.0p-53;
  return lo + (hi - lo) * unit;
}

}  // namespace

SmoothWarp::SmoothWarp(const Eigen::Vector3d& centre, const Eigen::Matrix3d& linear, std::vector<GaussianBump> bumps,
                       double turn_degrees, double pitch_degrees, double roll_degrees)
    : centre_(centre),
      linear_(linear),
      bumps_(std::move(bumps)),
      turn_degrees_(turn_degrees),
      pitch_degrees_(pitch_degrees),
      roll_degrees_(roll_degrees) {}

SmoothWarp SmoothWarp::with_flat_levels(double low, double high, double ramp) const {
  SmoothWarp w = *this;
  w.flat_low_ = low;
  w.flat_high_ = high;
  w.flat_ramp_ = ramp;
  return w;
}

double SmoothWarp::level_weight(double z, double* derivative) const {
  *derivative = 0;
  if (flat_ramp_ <= 0) return 1;
  if (z <= flat_low_ || z >= flat_high_) return 0;
  const auto step = [&](double t, double* slope) {  // cubic smoothstep of t = distance / ramp, and d/dz of it
    if (t >= 1) {
      *slope = 0;
      return 1.0;
    }
    *slope = 6 * t * (1 - t) / flat_ramp_;
    return t * t * (3 - 2 * t);
  };
  double rise_slope, fall_slope;
  const double rise = step((z - flat_low_) / flat_ramp_, &rise_slope),
               fall = step((flat_high_ - z) / flat_ramp_, &fall_slope);
  *derivative = rise_slope * fall - rise * fall_slope;
  return rise * fall;
}

Eigen::Vector3d SmoothWarp::unweighted(const Eigen::Vector3d& x) const {
  Eigen::Vector3d y = centre_ + linear_ * (x - centre_);
  for (const GaussianBump& b : bumps_) y += gaussian(b, x) * b.displacement;
  return y;
}

double SmoothWarp::along_z(double z) const { return centre_.z() + linear_(2, 2) * (z - centre_.z()); }

Eigen::Vector3d SmoothWarp::apply(const Eigen::Vector3d& x) const {
  Eigen::Vector3d y = unweighted(x);
  if (flat_ramp_ > 0) {
    double slope;
    const double along = along_z(x.z());
    y.z() = along + level_weight(x.z(), &slope) * (y.z() - along);
  }
  return y;
}

Eigen::MatrixXd SmoothWarp::apply_rows(const Eigen::MatrixXd& V) const {
  Eigen::MatrixXd W(V.rows(), 3);
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < V.rows(); ++i) W.row(i) = apply(Eigen::Vector3d(V.row(i).transpose())).transpose();
  return W;
}

Eigen::Matrix3d SmoothWarp::jacobian(const Eigen::Vector3d& x) const {
  Eigen::Matrix3d J = linear_;
  for (const GaussianBump& b : bumps_) {
    const Eigen::Vector3d grad = -gaussian(b, x) * (x - b.centre) / (b.sigma * b.sigma);
    J += b.displacement * grad.transpose();
  }
  if (flat_ramp_ > 0) {
    // Row z of d/dx [along(z) + w(z) n(x)], with n = (the unweighted W_z) - along.
    double slope;
    const double w = level_weight(x.z(), &slope);
    Eigen::RowVector3d row = w * J.row(2);
    row(2) += (1 - w) * linear_(2, 2) + slope * (unweighted(x).z() - along_z(x.z()));
    J.row(2) = row;
  }
  return J;
}

Eigen::Vector3d SmoothWarp::inverse(const Eigen::Vector3d& y) const {
  Eigen::Vector3d x = centre_ + linear_.inverse() * (y - centre_);
  for (int step = 0; step < 50; ++step) {
    const Eigen::Vector3d r = apply(x) - y;
    if (r.norm() < 1e-9) break;
    x -= jacobian(x).partialPivLu().solve(r);
  }
  return x;
}

double SmoothWarp::bump_gradient_bound() const {
  double L = 0;
  for (const GaussianBump& b : bumps_) L += b.displacement.norm() * kGradientPeak / b.sigma;
  return L;
}

double SmoothWarp::linear_min_singular_value() const {
  return Eigen::JacobiSVD<Eigen::Matrix3d>(linear_).singularValues().minCoeff();
}

SmoothWarp random_warp(std::uint64_t seed, const Eigen::Vector3d& centre, const Eigen::MatrixXd& anchors,
                       const RandomWarpRanges& ranges) {
  std::mt19937_64 rng(seed);
  Eigen::Matrix3d A;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      A(r, c) = r == c ? uniform(rng, 1 - ranges.max_scale, 1 + ranges.max_scale)
                       : uniform(rng, -ranges.max_shear, ranges.max_shear);
  std::vector<GaussianBump> bumps;
  for (int i = 0; i < ranges.bumps && anchors.rows() > 0; ++i) {
    GaussianBump b;
    const auto row = static_cast<Eigen::Index>(rng() % static_cast<std::uint64_t>(anchors.rows()));
    b.centre = anchors.row(row).transpose();
    Eigen::Vector3d direction;
    do {
      for (int k = 0; k < 3; ++k) direction(k) = uniform(rng, -1, 1);
    } while (direction.norm() < 0.1 || direction.norm() > 1);
    b.displacement = direction.normalized() * uniform(rng, 0.25, 1.0) * ranges.max_bump;
    b.sigma = uniform(rng, ranges.min_sigma, ranges.max_sigma);
    bumps.push_back(b);
  }
  // Drawn last, so that a seed's scale, shear and bumps do not depend on whether the warp turns, pitches or rolls.
  const double turn = ranges.max_turn > 0 ? uniform(rng, -ranges.max_turn, ranges.max_turn) : 0.0;
  const double pitch = ranges.max_pitch > 0 ? uniform(rng, -ranges.max_pitch, ranges.max_pitch) : 0.0;
  const double roll = ranges.max_roll > 0 ? uniform(rng, -ranges.max_roll, ranges.max_roll) : 0.0;
  A = Eigen::AngleAxisd(roll * M_PI / 180, Eigen::Vector3d::UnitY()) *
      Eigen::AngleAxisd(pitch * M_PI / 180, Eigen::Vector3d::UnitX()) *
      Eigen::AngleAxisd(turn * M_PI / 180, Eigen::Vector3d::UnitZ()) * A;
  SmoothWarp warp(centre, A, bumps, turn, pitch, roll);
  const double limit = 0.5 * warp.linear_min_singular_value(), L = warp.bump_gradient_bound();
  if (L > limit) {
    for (GaussianBump& b : bumps) b.displacement *= limit / L;
    warp = SmoothWarp(centre, A, bumps, turn, pitch, roll);
  }
  return warp;
}

SmoothWarp local_warp(const Eigen::Vector3d& at, const Eigen::Vector3d& displacement, double sigma) {
  const double needed = displacement.norm() * kGradientPeak / 0.5;
  return SmoothWarp(at, Eigen::Matrix3d::Identity(), {GaussianBump{at, displacement, std::max(sigma, needed)}});
}

double min_jacobian_determinant(const SmoothWarp& warp, const Eigen::Vector3d& lower, const Eigen::Vector3d& upper,
                                int steps) {
  double lowest = std::numeric_limits<double>::infinity();
  const double n = std::max(1, steps - 1);
  for (int i = 0; i < steps; ++i)
    for (int j = 0; j < steps; ++j)
      for (int k = 0; k < steps; ++k) {
        const Eigen::Vector3d t(i / n, j / n, k / n);
        const Eigen::Vector3d x = lower + t.cwiseProduct(upper - lower);
        lowest = std::min(lowest, warp.jacobian(x).determinant());
      }
  return lowest;
}

std::string warp_description(const SmoothWarp& warp) {
  const Eigen::Matrix3d A =
      Eigen::AngleAxisd(-warp.turn_degrees() * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
      Eigen::AngleAxisd(-warp.pitch_degrees() * M_PI / 180, Eigen::Vector3d::UnitX()).toRotationMatrix() *
      Eigen::AngleAxisd(-warp.roll_degrees() * M_PI / 180, Eigen::Vector3d::UnitY()).toRotationMatrix() * warp.linear();
  double shear = 0, bump = 0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      if (r != c) shear = std::max(shear, std::abs(A(r, c)));
  for (const GaussianBump& b : warp.bumps()) bump = std::max(bump, b.displacement.norm());
  char text[200];
  std::snprintf(text, sizeof text, "scale (%.3f, %.3f, %.3f), shear up to %.3f, %zu bump%s up to %.1f mm", A(0, 0),
                A(1, 1), A(2, 2), shear, warp.bumps().size(), warp.bumps().size() == 1 ? "" : "s", bump);
  std::string description = text;
  if (warp.turn_degrees() != 0) {
    char turn[40];
    std::snprintf(turn, sizeof turn, ", turned %.1f deg", warp.turn_degrees());
    description += turn;
  }
  if (warp.pitch_degrees() != 0) {
    char pitch[40];
    std::snprintf(pitch, sizeof pitch, ", pitched %.1f deg", warp.pitch_degrees());
    description += pitch;
  }
  if (warp.roll_degrees() != 0) {
    char roll[40];
    std::snprintf(roll, sizeof roll, ", rolled %.1f deg", warp.roll_degrees());
    description += roll;
  }
  if (warp.has_flat_levels()) description += ", end slices flat";
  return description;
}

}  // namespace facehex
