#pragma once
// Smooth invertible warps of space with a known answer, for correspondence benchmarks: a transfer onto a warped
// copy of a model should land every vertex where the warp took it.
//
//   W(x) = c + A (x - c) + sum_i d_i exp(-|x - p_i|^2 / (2 s_i^2))
//
// A is a linear map with det A > 0 (per-axis scale and shear), each Gaussian bump moves the points near p_i by up to
// |d_i|. The Jacobian is J(x) = A + sum_i d_i (grad g_i)^T, and |grad g_i| <= exp(-1/2) / s_i. When the bumps'
// gradient bound L = sum_i |d_i| exp(-1/2) / s_i is below the smallest singular value of A, W is injective on all of
// R^3 (|W(x) - W(y)| >= (sigma_min(A) - L) |x - y|) and det J > 0 everywhere: the warps made below keep L at most
// half of it.
//
// A warp of a CT can keep two slice planes flat (with_flat_levels: the scan's first and last slices). Its z component
// is then
//
//   W_z(x) = c_z + A_zz (z - c_z) + w(z) n(x),   n(x) = A_zx (x - c_x) + A_zy (y - c_y) + sum_i d_iz g_i(x),
//
// where w is 1 between the levels but for a ramp of `ramp` mm at each, falls to 0 at both (a product of two cubic
// smoothsteps) and is 0 beyond them: W maps each plane z = const outside the ramps' interior to a plane z = const, so
// a volume cut at those levels stays a volume cut in slice planes. The x and y components are unchanged. The bound L
// does not cover the term w'(z) n(x) of the Jacobian: min_jacobian_determinant checks such a warp.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace facehex {

struct GaussianBump {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();        // mm
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();  // mm, at the centre
  double sigma = 1;                                        // mm
};

class SmoothWarp {
 public:
  SmoothWarp() = default;
  // turn_degrees, pitch_degrees, roll_degrees: how far `linear` turns about the z axis, then about the x axis and then
  // about the y axis (linear = R_y(roll) R_x(pitch) R_z(turn) times scale and shear), for descriptions.
  SmoothWarp(const Eigen::Vector3d& centre, const Eigen::Matrix3d& linear, std::vector<GaussianBump> bumps,
             double turn_degrees = 0, double pitch_degrees = 0, double roll_degrees = 0);

  // This warp with the slice planes z = low and z = high kept flat (the header), low < high, ramp > 0 (mm).
  SmoothWarp with_flat_levels(double low, double high, double ramp) const;

  Eigen::Vector3d apply(const Eigen::Vector3d& x) const;
  Eigen::MatrixXd apply_rows(const Eigen::MatrixXd& V) const;  // each row of #V x 3
  Eigen::Matrix3d jacobian(const Eigen::Vector3d& x) const;
  // The x with W(x) = y, by Newton steps from the linear part's inverse (to 1e-9 mm).
  Eigen::Vector3d inverse(const Eigen::Vector3d& y) const;
  // The bound L of the header and the smallest singular value of A: L < sigma_min(A) makes W invertible.
  double bump_gradient_bound() const;
  double linear_min_singular_value() const;

  const Eigen::Vector3d& centre() const { return centre_; }
  const Eigen::Matrix3d& linear() const { return linear_; }
  const std::vector<GaussianBump>& bumps() const { return bumps_; }
  double turn_degrees() const { return turn_degrees_; }
  double pitch_degrees() const { return pitch_degrees_; }
  double roll_degrees() const { return roll_degrees_; }
  // A pitch or a roll tilts the slice planes across the whole scan.
  bool tilts_slices() const { return pitch_degrees_ != 0 || roll_degrees_ != 0; }
  bool has_flat_levels() const { return flat_ramp_ > 0; }

 private:
  // The weight w(z) of the header and its derivative; 1 and 0 without flat levels.
  double level_weight(double z, double* derivative) const;
  Eigen::Vector3d unweighted(const Eigen::Vector3d& x) const;  // c + A (x - c) + sum_i d_i g_i(x)
  double along_z(double z) const;                              // c_z + A_zz (z - c_z)

  Eigen::Vector3d centre_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d linear_ = Eigen::Matrix3d::Identity();
  std::vector<GaussianBump> bumps_;
  double turn_degrees_ = 0, pitch_degrees_ = 0, roll_degrees_ = 0;
  double flat_low_ = 0, flat_high_ = 0, flat_ramp_ = 0;  // ramp 0: no flat levels
};

// The ranges a seeded random warp draws from.
struct RandomWarpRanges {
  double max_scale = 0.12;  // each axis scaled by a factor in [1 - max_scale, 1 + max_scale]
  double max_shear = 0.08;  // each off-diagonal entry of A in [-max_shear, max_shear]
  int bumps = 4;            // Gaussian bumps centred on points drawn from `anchors`
  double max_bump = 8.0;    // mm, |d_i| up to this (scaled down to keep L <= sigma_min(A) / 2)
  double min_sigma = 25.0;  // mm
  double max_sigma = 40.0;  // mm
  double max_turn = 0.0;    // degrees: A is turned about the vertical (z) axis by an angle in [-max_turn, max_turn]
  double max_pitch = 0.0;   // degrees: and then about the lateral (x) axis by one in [-max_pitch, max_pitch]
  double max_roll = 0.0;    // degrees: and then about the front-to-back (y) axis by one in [-max_roll, max_roll]
};

// A warp drawn from the ranges with std::mt19937_64(seed) (whose sequence the C++ standard fixes, converted to
// doubles by hand, so a seed gives the same warp bit for bit on every platform), about `centre`, its bumps centred
// on rows of `anchors` (#A x 3, e.g. a model's skin vertices).
SmoothWarp random_warp(std::uint64_t seed, const Eigen::Vector3d& centre, const Eigen::MatrixXd& anchors,
                       const RandomWarpRanges& ranges = {});

// A warp that is one bump: the points near `at` move by `displacement`; sigma is raised where needed to keep
// L <= 1/2.
SmoothWarp local_warp(const Eigen::Vector3d& at, const Eigen::Vector3d& displacement, double sigma);

// The smallest det J over a regular grid of `steps` points per axis spanning [lower, upper].
double min_jacobian_determinant(const SmoothWarp& warp, const Eigen::Vector3d& lower, const Eigen::Vector3d& upper,
                                int steps);

// One line for reports: "scale (1.05, 0.93, 1.10), shear up to 0.04, 4 bumps up to 7.2 mm[, turned 6.2 deg][, pitched
// -8.1 deg][, rolled 9.0 deg][, end slices flat]".
std::string warp_description(const SmoothWarp& warp);

}  // namespace facehex
