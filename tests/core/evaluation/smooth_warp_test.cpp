// Smooth warps with known seeds: invertible everywhere on a grid, reproducible bit for bit, inverted by inverse(),
// their Jacobian the derivative of apply(), and a warped volume holding at W(x) what the original holds at x.
#include "core/evaluation/smooth_warp.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "core/evaluation/warp_volume.h"
#include "core/util/error.h"

namespace facehex {
namespace {

// Anchor points spread over a face-sized box.
Eigen::MatrixXd anchors() {
  Eigen::MatrixXd A(27, 3);
  int r = 0;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k) A.row(r++) << 60.0 * i, 40.0 * j, 60.0 * k;
  return A;
}

// dW/dx at x by central differences.
Eigen::Matrix3d central_difference_jacobian(const SmoothWarp& w, const Eigen::Vector3d& x) {
  const double h = 1e-5;
  Eigen::Matrix3d fd;
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(a);
    fd.col(a) = (w.apply(x + e) - w.apply(x - e)) / (2 * h);
  }
  return fd;
}

TEST(SmoothWarp, RandomWarpsArePositivelyOrientedEverywhereOnAGrid) {
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const SmoothWarp w = random_warp(seed, Eigen::Vector3d(5, -3, 2), anchors());
    EXPECT_EQ(w.bumps().size(), 4u);
    EXPECT_LE(w.bump_gradient_bound(), 0.5 * w.linear_min_singular_value() + 1e-12) << "seed " << seed;
    EXPECT_GT(min_jacobian_determinant(w, Eigen::Vector3d::Constant(-150), Eigen::Vector3d::Constant(150), 31), 0.2)
        << "seed " << seed;
    for (int r = 0; r < 3; ++r) {
      EXPECT_LE(std::abs(w.linear()(r, r) - 1), 0.12);
      for (int c = 0; c < 3; ++c) {
        if (r != c) {
          EXPECT_LE(std::abs(w.linear()(r, c)), 0.08);
        }
      }
    }
  }
}

TEST(SmoothWarp, AStrongBumpIsWidenedUntilItIsInvertible) {
  // 20 mm over a sigma of 5 mm would fold space (L = 2.4); local_warp widens it to L = 1/2.
  const SmoothWarp w = local_warp(Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 20, 0), 5.0);
  EXPECT_NEAR(w.bump_gradient_bound(), 0.5, 1e-12);
  EXPECT_GT(min_jacobian_determinant(w, Eigen::Vector3d::Constant(-100), Eigen::Vector3d::Constant(100), 41), 0.49);
  EXPECT_NEAR((w.apply(Eigen::Vector3d::Zero()) - Eigen::Vector3d(0, 20, 0)).norm(), 0, 1e-12);
}

TEST(SmoothWarp, ASeedGivesTheSameWarpBitForBit) {
  const SmoothWarp a = random_warp(42, Eigen::Vector3d::Zero(), anchors()),
                   b = random_warp(42, Eigen::Vector3d::Zero(), anchors()),
                   c = random_warp(43, Eigen::Vector3d::Zero(), anchors());
  EXPECT_TRUE((a.linear().array() == b.linear().array()).all());
  ASSERT_EQ(a.bumps().size(), b.bumps().size());
  for (size_t i = 0; i < a.bumps().size(); ++i) {
    EXPECT_TRUE((a.bumps()[i].centre.array() == b.bumps()[i].centre.array()).all());
    EXPECT_TRUE((a.bumps()[i].displacement.array() == b.bumps()[i].displacement.array()).all());
    EXPECT_EQ(a.bumps()[i].sigma, b.bumps()[i].sigma);
  }
  EXPECT_FALSE((a.linear().array() == c.linear().array()).all());
  const Eigen::MatrixXd V = anchors();
  EXPECT_TRUE((a.apply_rows(V).array() == b.apply_rows(V).array()).all());
}

// A turned warp (a head turned in the scanner) is the same seed's warp with its linear part turned about z: the
// scale, shear and bumps do not change with the turn, and the description gives both.
TEST(SmoothWarp, ATurnTurnsTheSameSeedsWarp) {
  RandomWarpRanges turned;
  turned.max_turn = 10;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const SmoothWarp plain = random_warp(seed, Eigen::Vector3d(5, -3, 2), anchors()),
                     w = random_warp(seed, Eigen::Vector3d(5, -3, 2), anchors(), turned);
    EXPECT_LE(std::abs(w.turn_degrees()), 10.0);
    EXPECT_GT(std::abs(w.turn_degrees()), 0.0);
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(w.turn_degrees() * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    EXPECT_TRUE(w.linear().isApprox(R * plain.linear(), 1e-12)) << seed;
    ASSERT_EQ(w.bumps().size(), plain.bumps().size());
    for (size_t i = 0; i < w.bumps().size(); ++i) EXPECT_EQ(w.bumps()[i].centre, plain.bumps()[i].centre);
    EXPECT_EQ(plain.turn_degrees(), 0.0);
    const std::string a = warp_description(plain), b = warp_description(w);
    EXPECT_EQ(b.substr(0, a.size()), a) << b;  // the same scale, shear and bumps
    EXPECT_NE(b.find(", turned "), std::string::npos) << b;
    EXPECT_EQ(a.find("turned"), std::string::npos) << a;
    EXPECT_GT(min_jacobian_determinant(w, Eigen::Vector3d::Constant(-100), Eigen::Vector3d::Constant(100), 9), 0);
  }
}

// `w` is `base` with its linear part then turned about `axis` by `degrees`: the same scale, shear, bumps and earlier
// turns in its description, which says `word` too, and invertible about the anchors.
void expect_turned_about(const SmoothWarp& base, const SmoothWarp& w, const Eigen::Vector3d& axis, double degrees,
                         const std::string& word) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(degrees * M_PI / 180, axis).toRotationMatrix();
  EXPECT_TRUE(w.linear().isApprox(R * base.linear(), 1e-12)) << word;
  const std::string a = warp_description(base), b = warp_description(w);
  EXPECT_EQ(b.substr(0, a.size()), a) << b;
  EXPECT_NE(b.find(word), std::string::npos) << b;
  EXPECT_GT(min_jacobian_determinant(w, Eigen::Vector3d::Constant(-100), Eigen::Vector3d::Constant(100), 9), 0);
}

// A pitched warp (a head nodding in the scanner) is the same seed's warp, turned as it would be, with its linear part
// then turned about x.
TEST(SmoothWarp, APitchPitchesTheSameSeedsTurnedWarp) {
  RandomWarpRanges turned, pitched;
  turned.max_turn = pitched.max_turn = 10;
  pitched.max_pitch = 15;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const SmoothWarp t = random_warp(seed, Eigen::Vector3d(5, -3, 2), anchors(), turned),
                     w = random_warp(seed, Eigen::Vector3d(5, -3, 2), anchors(), pitched);
    EXPECT_EQ(w.turn_degrees(), t.turn_degrees());
    EXPECT_LE(std::abs(w.pitch_degrees()), 15.0);
    EXPECT_GT(std::abs(w.pitch_degrees()), 0.0);
    expect_turned_about(t, w, Eigen::Vector3d::UnitX(), w.pitch_degrees(), ", pitched ");
  }
}

// A rolled warp (a head tilted towards a shoulder) is the same seed's pitched warp with its linear part then turned
// about y; a seed drawn without a roll is the warp it was before rolls were drawn.
TEST(SmoothWarp, ARollRollsTheSameSeedsPitchedWarp) {
  RandomWarpRanges pitched, rolled;
  pitched.max_turn = rolled.max_turn = 10;
  pitched.max_pitch = rolled.max_pitch = 15;
  rolled.max_roll = 20;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const SmoothWarp p = random_warp(seed, Eigen::Vector3d(5, -3, 2), anchors(), pitched),
                     w = random_warp(seed, Eigen::Vector3d(5, -3, 2), anchors(), rolled);
    EXPECT_EQ(p.roll_degrees(), 0.0);
    EXPECT_FALSE(random_warp(seed, Eigen::Vector3d(5, -3, 2), anchors(), RandomWarpRanges{}).tilts_slices());
    EXPECT_TRUE(w.tilts_slices());
    EXPECT_EQ(w.turn_degrees(), p.turn_degrees());
    EXPECT_EQ(w.pitch_degrees(), p.pitch_degrees());
    EXPECT_LE(std::abs(w.roll_degrees()), 20.0);
    EXPECT_GT(std::abs(w.roll_degrees()), 0.0);
    expect_turned_about(p, w, Eigen::Vector3d::UnitY(), w.roll_degrees(), ", rolled ");
  }
}

TEST(SmoothWarp, InverseUndoesApplyAndTheJacobianIsItsDerivative) {
  const SmoothWarp w = random_warp(3, Eigen::Vector3d(1, 2, 3), anchors());
  const Eigen::MatrixXd V = anchors() * 0.9;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Eigen::Vector3d x = V.row(i).transpose();
    EXPECT_LT((w.inverse(w.apply(x)) - x).norm(), 1e-8);
    EXPECT_LT((central_difference_jacobian(w, x) - w.jacobian(x)).norm(), 1e-7);
  }
}

TEST(WarpVolume, TheWarpedVolumeHoldsAtWOfXWhatTheOriginalHoldsAtX) {
  // A smooth blob on a 1 mm grid: trilinear sampling of it is exact to well below its 1e-2 variation per voxel.
  GridGeometry g;
  g.dims = {81, 81, 81};
  g.origin = Eigen::Vector3d::Constant(-40);
  Field f(g, 0.0f);
  const auto blob = [](const Eigen::Vector3d& x) { return 1000.0 * std::exp(-x.squaredNorm() / (2 * 12.0 * 12.0)); };
  for (int k = 0; k < 81; ++k)
    for (int j = 0; j < 81; ++j)
      for (int i = 0; i < 81; ++i) f(i, j, k) = static_cast<float>(blob(g.point(i, j, k)));
  const SmoothWarp w =
      random_warp(5, Eigen::Vector3d::Zero(), anchors() * 0.3, RandomWarpRanges{0.1, 0.05, 3, 6.0, 15.0, 20.0});
  const Field warped = warp_volume(f, w);
  // Across (x, y) the warped grid holds the image of the original box; in z only the levels the original covers
  // across its whole area: its end slices map into the original's slices wherever they lie inside the original's box.
  for (int a = 0; a < 2; ++a) {
    EXPECT_LE(warped.geometry.lower(a), w.apply(Eigen::Vector3d::Constant(-40))(a));
    EXPECT_GE(warped.geometry.upper(a), w.apply(Eigen::Vector3d::Constant(40))(a));
  }
  int end_columns = 0;
  for (const int k : {0, warped.geometry.dims[2] - 1})
    for (int j = 0; j < warped.geometry.dims[1]; j += 3)
      for (int i = 0; i < warped.geometry.dims[0]; i += 3) {
        const Eigen::Vector3d x = w.inverse(warped.geometry.point(i, j, k));
        if (std::abs(x.x()) > 40 || std::abs(x.y()) > 40) continue;
        ++end_columns;
        EXPECT_LE(std::abs(x.z()), 40.5) << "slice " << k << " column (" << i << ", " << j << ")";
      }
  EXPECT_GT(end_columns, 100);
  double worst = 0;
  for (int i = -25; i <= 25; i += 5)
    for (int j = -25; j <= 25; j += 5)
      for (int k = -25; k <= 25; k += 5) {
        const Eigen::Vector3d x(i + 0.3, j - 0.2, k + 0.1);
        worst = std::max(worst, std::abs(sample(warped, w.apply(x)) - blob(x)));
      }
  EXPECT_LT(worst, 10.0);  // 1 % of the blob's peak: two trilinear interpolations of a 12 mm Gaussian
  EXPECT_GT(worst, 0.0);
  // Beyond the image of the original's box, the original's lowest value (the blob's tail at the box's corner).
  const float lowest = *std::min_element(f.data.begin(), f.data.end());
  int outside = 0;
  const GridGeometry& wg = warped.geometry;
  for (int k = 0; k < wg.dims[2]; k += 7)
    for (int j = 0; j < wg.dims[1]; j += 7)
      for (int i = 0; i < wg.dims[0]; i += 7)
        if ((w.inverse(wg.point(i, j, k)).array().abs() > 40.5).any()) {
          ++outside;
          EXPECT_EQ(warped(i, j, k), lowest);
        }
  EXPECT_GT(outside, 0);
}

// A CT warp with flat end slices: the planes z = low and z = high (and all beyond) map onto planes of constant z,
// the middle moves as the warp without them, the Jacobian is still the derivative of apply() (in the ramps too) and the
// warp is invertible on a head-sized box for the benchmark's moderate and strong ranges.
TEST(SmoothWarp, FlatLevelsKeepTheEndSlicesFlatAndTheMiddleAsItWas) {
  const RandomWarpRanges moderate{0.08, 0.04, 4, 4.0, 25.0, 40.0}, strong{0.10, 0.04, 6, 10.0, 25.0, 40.0, 10.0};
  for (const RandomWarpRanges& ranges : {moderate, strong})
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
      const SmoothWarp plain = random_warp(seed, Eigen::Vector3d(5, -3, 2), anchors(), ranges),
                       w = plain.with_flat_levels(-70, 70, 30);
      EXPECT_NE(warp_description(w).find("end slices flat"), std::string::npos);
      for (const double z : {-70.0, -80.0, 70.0, 75.0}) {
        const double level = w.apply(Eigen::Vector3d(0, 0, z)).z();
        for (int i = -100; i <= 100; i += 25)
          for (int j = -100; j <= 100; j += 25) EXPECT_NEAR(w.apply(Eigen::Vector3d(i, j, z)).z(), level, 1e-9);
      }
      bool bends = false;  // without flat levels the end slice is not flat
      for (int i = -100; i <= 100; i += 25)
        bends = bends || std::abs(plain.apply(Eigen::Vector3d(i, 50, 70)).z() -
                                  plain.apply(Eigen::Vector3d(0, 0, 70)).z()) > 0.5;
      EXPECT_TRUE(bends) << seed;
      for (int i = -60; i <= 60; i += 30)
        for (int k = -30; k <= 30; k += 15) {
          const Eigen::Vector3d x(i, 20, k);
          EXPECT_LT((w.apply(x) - plain.apply(x)).norm(), 1e-12) << "beyond the ramps the warp is unchanged";
        }
      for (const double z : {-65.0, -52.0, -41.0, 43.0, 58.0, 69.0}) {  // in the ramps
        const Eigen::Vector3d x(17, -23, z);
        EXPECT_LT((central_difference_jacobian(w, x) - w.jacobian(x)).norm(), 1e-6) << "seed " << seed << " z " << z;
        EXPECT_LT((w.inverse(w.apply(x)) - x).norm(), 1e-8);
      }
      EXPECT_GT(min_jacobian_determinant(w, Eigen::Vector3d(-120, -120, -90), Eigen::Vector3d(120, 120, 90), 31), 0.2)
          << "seed " << seed;
    }
}

// A volume warped with flat end slices keeps every slice level the original has, its ends at the images of the
// original's end slices.
TEST(WarpVolume, FlatEndSlicesKeepAllOfTheOriginalsLevels) {
  GridGeometry g;
  g.dims = {41, 41, 31};
  g.spacing = Eigen::Vector3d(2, 2, 3);
  g.origin = Eigen::Vector3d(-40, -40, -45);
  Field f(g, 1.0f);
  const SmoothWarp w =
      random_warp(2, Eigen::Vector3d::Zero(), anchors() * 0.5, RandomWarpRanges{0.08, 0.04, 4, 4.0, 25.0, 40.0})
          .with_flat_levels(g.lower(2), g.upper(2), 20);
  const Field warped = warp_volume(f, w);
  const double bottom = w.apply(Eigen::Vector3d(0, 0, g.lower(2))).z(),
               top = w.apply(Eigen::Vector3d(0, 0, g.upper(2))).z();
  EXPECT_NEAR(warped.geometry.lower(2), bottom, 1e-9);
  EXPECT_LE(warped.geometry.upper(2), top + 1e-9);
  EXPECT_GT(warped.geometry.upper(2), top - g.spacing.z());
  // The end slices hold the original's tissue wherever their columns lie inside the original's box.
  int inside = 0;
  for (const int k : {0, warped.geometry.dims[2] - 1})
    for (int j = 0; j < warped.geometry.dims[1]; j += 2)
      for (int i = 0; i < warped.geometry.dims[0]; i += 2) {
        const Eigen::Vector3d x = w.inverse(warped.geometry.point(i, j, k));
        if (std::abs(x.x()) > 39 || std::abs(x.y()) > 39) continue;
        ++inside;
        EXPECT_EQ(warped(i, j, k), 1.0f);
      }
  EXPECT_GT(inside, 200);
}

// A head-sized ellipsoid of tissue (semi-axes 70, 100, 110 mm about (0, 0, 0)) in air, with a 2 mm noise-free skin
// edge: the warp frame's anchors are its face-on surface, the most anterior tissue of each column, no deeper than
// kWarpFrameDepth behind its front; none on the back of the head; the centre is their mean.
TEST(WarpVolume, ACtsWarpFrameIsItsFaceOnSkinFromTheVolumeAlone) {
  GridGeometry g;
  g.dims = {81, 121, 121};
  g.spacing = Eigen::Vector3d::Constant(2);
  g.origin = Eigen::Vector3d(-80, -120, -120);
  Field f(g, -1000.0f);
  const Eigen::Vector3d axes(70, 100, 110);
  const auto inside = [&](const Eigen::Vector3d& x) { return x.cwiseQuotient(axes).squaredNorm() <= 1; };
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i)
        if (inside(g.point(i, j, k))) f(i, j, k) = (i + j + k) % 5 == 0 ? 400.0f : 40.0f;  // soft tissue and some bone
  const CtWarpFrame frame = ct_warp_frame(f);
  ASSERT_GT(frame.anchors.rows(), 1000);
  for (Eigen::Index r = 0; r < frame.anchors.rows(); ++r) {
    const Eigen::Vector3d p = frame.anchors.row(r).transpose();
    EXPECT_TRUE(inside(p)) << p.transpose();
    EXPECT_FALSE(inside(p + Eigen::Vector3d(0, 2, 0))) << "not the front of its column: " << p.transpose();
    EXPECT_GE(p.y(), 100 - kWarpFrameDepth - 2) << p.transpose();
  }
  EXPECT_LT((frame.centre - frame.anchors.colwise().mean().transpose()).norm(), 1e-9);
  EXPECT_NEAR(frame.centre.x(), 0, 1);  // the ellipsoid's front is symmetric in x and z
  EXPECT_NEAR(frame.centre.z(), 0, 1);
  EXPECT_GT(frame.centre.y(), 40);
  // A volume with nothing above its skin threshold (here, no contrast at all) has no frame.
  EXPECT_THROW(ct_warp_frame(Field(g, 5.0f)), Error);
}

}  // namespace
}  // namespace facehex
