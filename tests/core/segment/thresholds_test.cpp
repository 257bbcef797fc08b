#include "core/segment/thresholds.h"

#include <gtest/gtest.h>

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

TEST(Thresholds, ConstantVolumeIsAnError) {
  Field f(GridGeometry{{4, 4, 4}, Eigen::Vector3d::Ones(), Eigen::Vector3d::Zero()}, 7.0f);
  EXPECT_THROW(estimate_thresholds(f), Error);
}

}  // namespace
}  // namespace facehex
