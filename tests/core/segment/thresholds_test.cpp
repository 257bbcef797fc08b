#include "core/segment/thresholds.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <random>
#include <vector>

#include "core/util/error.h"
#include "tests/core/segment/phantom.h"

namespace facehex {
namespace {

TEST(Thresholds, PhantomSkinBetweenAirAndTissueBoneAboveTissue) {
  const TissueThresholds t = estimate_thresholds(testing::ellipsoid_phantom().intensity);
  EXPECT_GT(t.skin, 100);
  EXPECT_LT(t.skin, 900);
  EXPECT_GT(t.bone, 1040);  // above the tissue's noise (+-40)
  EXPECT_LT(t.bone, 1960);  // below the bone's
}

// A volume of known modes: air around 0 and soft tissue around 1000 (each +-40, triangular), a partial-volume
// population between them (deepest at a chosen intensity) and a bone tail. The skin threshold is half way between the
// modes whatever the population between them (the valley's deepest point moves with it), and a scanner's fill outside
// its field of view (many voxels at one value far below air) does not move it.
Field two_modes(int between_at, float fill, int fill_count) {
  std::vector<float> values;
  // The sum of two even spreads of 20 steps: a triangular distribution peaked at `centre`, +-40.
  const auto mode = [&](float centre, int repeats) {
    for (int r = 0; r < repeats; ++r)
      for (int a = 0; a < 20; ++a)
        for (int b = 0; b < 20; ++b) values.push_back(centre + 40.0f * ((a + b) / 19.0f - 1.0f));
  };
  mode(0.0f, 100);
  mode(1000.0f, 50);
  for (int v = 50; v <= 950; v += 5)  // partial volume: a valley whose deepest point is at between_at
    for (int n = 0; n <= std::abs(v - between_at) / 50; ++n) values.push_back(static_cast<float>(v));
  for (int i = 0; i < 2000; ++i) values.push_back(1300.0f + static_cast<float>(i % 700));  // bone
  for (int i = 0; i < fill_count; ++i) values.push_back(fill);
  Field f(GridGeometry{{static_cast<int>(values.size()), 1, 1}, Eigen::Vector3d::Ones(), Eigen::Vector3d::Zero()},
          0.0f);
  f.data = values;
  return f;
}

TEST(Thresholds, SkinIsHalfWayBetweenTheModesWhateverLiesBetweenThemAndWithAFieldOfViewFill) {
  const double bin = (2000.0 + 40.0) / 512;  // the histogram's bin width on the volume without fill
  for (const int between_at : {150, 400, 700}) {
    const TissueThresholds t = estimate_thresholds(two_modes(between_at, 0.0f, 0));
    EXPECT_NEAR(t.skin, 500, 3 * bin) << "partial volume at " << between_at;
    EXPECT_GT(t.bone, 1040);
    EXPECT_LT(t.bone, 1400);
  }
  // A fill at -3000 with more voxels than the air: without leaving it out, it would be the air's peak.
  const TissueThresholds filled = estimate_thresholds(two_modes(400, -3000.0f, 80000));
  EXPECT_NEAR(filled.skin, 500, 3 * (5000.0 / 512)) << "the fill outside the field of view";
}

TEST(Thresholds, OnABlurredCtTheBoneThresholdFollowsTheSoftTissuePeaksWidthNotTheBoneEdgesPlateau) {
  // Air and soft tissue as Gaussian peaks (sigma 30), bone at 2000, and between soft tissue and bone the plateau a blur
  // spreads a bone's edges into: a tenth of the peak's height, from 1000 to 2000. The histogram never falls to the
  // tail fraction before the bone, so the tail rule ends at the bone; the peak-width rule puts the threshold where a
  // Gaussian of the peak's width falls to it, 2.45 sigma above the mode, as on the CT before the blur.
  std::vector<float> values;
  std::mt19937 random(4);
  std::normal_distribution<float> spread(0.0f, 30.0f);
  for (int i = 0; i < 200000; ++i) values.push_back(spread(random));
  for (int i = 0; i < 200000; ++i) values.push_back(1000.0f + spread(random));
  // A tenth of the peak's height (200000 / (30 sqrt(2 pi)) per unit) over 1000 units.
  for (int i = 0; i < 266000; ++i) values.push_back(1000.0f + 1000.0f * static_cast<float>(i) / 266000);
  for (int i = 0; i < 20000; ++i) values.push_back(2000.0f + spread(random));
  Field f(GridGeometry{{static_cast<int>(values.size()), 1, 1}, Eigen::Vector3d::Ones(), Eigen::Vector3d::Zero()},
          0.0f);
  f.data = values;
  const double bin = 2300.0 / 512;  // about the values' range over the histogram's bins
  const TissueThresholds tail = estimate_thresholds(f);
  EXPECT_GT(tail.bone, 1800);  // lost in the plateau
  const TissueThresholds width = estimate_thresholds(f, BoneThresholdRule::peak_width);
  EXPECT_NEAR(width.bone, 1000 + 2.45 * 30, 2 * bin);
  EXPECT_EQ(width.skin, tail.skin);
  IntensityModes modes;
  estimate_thresholds(f, BoneThresholdRule::histogram_tail, &modes);
  EXPECT_NEAR(modes.air, 0, 2 * bin);
  EXPECT_NEAR(modes.tissue, 1000, 2 * bin);
}

TEST(Thresholds, ConstantVolumeIsAnError) {
  Field f(GridGeometry{{4, 4, 4}, Eigen::Vector3d::Ones(), Eigen::Vector3d::Zero()}, 7.0f);
  EXPECT_THROW(estimate_thresholds(f), Error);
}

}  // namespace
}  // namespace facehex
