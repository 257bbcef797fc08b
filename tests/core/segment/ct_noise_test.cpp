#include "core/segment/ct_noise.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace facehex {
namespace {

// A CT of slabs along x, air (0), soft tissue (1000) and bone (2000), on anisotropic voxels, with white Gaussian noise
// of `sigma` drawn from `seed`.
Field slabs(double sigma, unsigned seed, const Eigen::Vector3d& spacing = Eigen::Vector3d(0.8, 0.8, 1.5)) {
  Field f(GridGeometry{{96, 80, 40}, spacing, Eigen::Vector3d::Zero()}, 0.0f);
  std::mt19937 random(seed);
  std::normal_distribution<float> noise(0.0f, static_cast<float>(sigma));
  for (int k = 0; k < f.geometry.dims[2]; ++k)
    for (int j = 0; j < f.geometry.dims[1]; ++j)
      for (int i = 0; i < f.geometry.dims[0]; ++i)
        f(i, j, k) = (i < 40 ? 0.0f : i < 80 ? 1000.0f : 2000.0f) + (sigma > 0 ? noise(random) : 0.0f);
  return f;
}

// The noise of `f` between its histogram's modes, as the segmentation measures it.
CtNoise noise_of(const Field& f) {
  IntensityModes modes;
  estimate_thresholds(f, BoneThresholdRule::histogram_tail, &modes);
  return measure_ct_noise(f, modes);
}

TEST(CtNoise, MeasuresWhiteNoiseOfAKnownSigma) {
  for (const unsigned seed : {1u, 2u, 3u})
    for (const double sigma : {15.0, 50.0, 100.0}) {
      const CtNoise n = noise_of(slabs(sigma, seed));
      EXPECT_NEAR(n.contrast, 1000, 40) << sigma;
      EXPECT_NEAR(n.sigma, sigma, 0.1 * sigma) << "sigma " << sigma << ", seed " << seed;
    }
}

TEST(CtNoise, AQuietCtIsLeftAsItIsAndANoisyOneBlurredToADiagnosticCtsNoise) {
  const CtNoise clean = noise_of(slabs(0, 1));
  EXPECT_EQ(clean.sigma, 0);
  EXPECT_EQ(clean.blur, 0);
  const CtNoise quiet = noise_of(slabs(15, 1));  // 1.5 % of the contrast
  EXPECT_EQ(quiet.blur, 0);
  EXPECT_EQ(quiet.sigma_after, quiet.sigma);
  for (const double sigma : {50.0, 100.0}) {
    const CtNoise noisy = noise_of(slabs(sigma, 2));
    EXPECT_GT(noisy.blur, 0) << sigma;
    EXPECT_LT(noisy.blur, kMostDenoisingBlur) << sigma;
    EXPECT_NEAR(noisy.sigma_after, kDiagnosticNoise * noisy.contrast, 0.01 * noisy.contrast) << sigma;
  }
  // On coarse voxels, noisier than the largest blur brings down: that blur, and what it leaves said.
  const CtNoise worst = noise_of(slabs(200, 3, Eigen::Vector3d(2, 2, 3)));
  EXPECT_EQ(worst.blur, kMostDenoisingBlur);
  EXPECT_GT(worst.sigma_after, kDiagnosticNoise * worst.contrast);
}

TEST(CtNoise, TheBlurLeavesTheNoiseItPredicts) {
  // Pure white noise blurred as the segmentation blurs a noisy CT: its standard deviation, away from the grid's
  // border, is what white_noise_after_blur says.
  Field f(GridGeometry{{64, 64, 48}, Eigen::Vector3d(0.8, 0.8, 1.5), Eigen::Vector3d::Zero()}, 0.0f);
  std::mt19937 random(5);
  std::normal_distribution<float> noise(0.0f, 1.0f);
  for (float& v : f.data) v = noise(random);
  for (const double blur : {0.5, 1.0, 1.7}) {
    const Field smooth = gaussian_smooth(f, blur);
    double sum = 0, sum2 = 0;
    int count = 0;
    for (int k = 8; k < 40; ++k)
      for (int j = 12; j < 52; ++j)
        for (int i = 12; i < 52; ++i) sum += smooth(i, j, k), sum2 += smooth(i, j, k) * smooth(i, j, k), ++count;
    const double sd = std::sqrt(sum2 / count - (sum / count) * (sum / count));
    EXPECT_NEAR(sd, white_noise_after_blur(f.geometry.spacing, blur), 0.05 * sd) << blur;
  }
  EXPECT_EQ(white_noise_after_blur(f.geometry.spacing, 0), 1);
}

}  // namespace
}  // namespace facehex
