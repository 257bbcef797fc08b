#include "core/segment/stomion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <string>

#include "core/face/landmark_file.h"
#include "core/segment/ct_volume.h"
#include "core/segment/thresholds.h"
#include "core/util/resources.h"
#include "tests/core/segment/phantom.h"

namespace facehex {
namespace {

// Lips in their head frame (plane x = 0, +y anterior) whose front recedes sideways, meeting at z = 0 in a V-shaped
// slit kSlitDepth deep and 3 mm tall; parted lips instead leave a gap `gap` tall with the teeth kTeeth behind it.
struct LipsPhantom {
  static constexpr double kFront = 20, kSlitDepth = 3, kTeeth = 15;
  bool parted = false, slit = true;
  double gap = 8;
  double front(double x, double z) const {
    const double lips = kFront - 0.01 * x * x - 0.02 * z * z;
    if (parted) return std::abs(z) < gap / 2 ? kFront - kTeeth : lips;
    return lips - (slit ? std::max(0.0, kSlitDepth * (1 - std::abs(z) / 1.5)) : 0.0);
  }
};

// The phantom's CT and its labralia (the lips' fronts `reach` mm above and below the middle), in the model's frame.
struct LipsCt {
  Field ct;
  Eigen::Vector3d upper, lower;
};

LipsCt lips_ct(const LipsPhantom& lips, const MidSagittalPlane& plane, double reach) {
  const HeadTurn frame = head_turn_of(plane);
  const auto on_front = [&](double z) { return frame.to_model(Eigen::Vector3d(0, lips.front(0, z), z)); };
  return {testing::face_front_phantom([&lips](double x, double z) { return lips.front(x, z); }, frame), on_front(reach),
          on_front(-reach)};
}

std::optional<CtLandmark> stomion_of(const LipsPhantom& lips, const MidSagittalPlane& plane) {
  const LipsCt c = lips_ct(lips, plane, 6);
  return find_stomion(c.ct, 0, plane, c.upper, c.lower);
}

double gap_of(const LipsPhantom& lips, const MidSagittalPlane& plane) {
  const LipsCt c = lips_ct(lips, plane, 8);  // beyond the widest gap tried
  return parted_lips_gap(c.ct, 0, plane, c.upper, c.lower);
}

TEST(Stomion, TheBottomOfTheClosedLipsSlitUprightAndTurned) {
  for (const double turn_degrees : {0.0, 10.0, -20.0}) {
    MidSagittalPlane plane;
    plane.turn = std::tan(turn_degrees * M_PI / 180);
    plane.y = 10;
    const std::optional<CtLandmark> found = stomion_of(LipsPhantom{}, plane);
    ASSERT_TRUE(found) << "turned " << turn_degrees;
    EXPECT_FALSE(found->estimated);
    const Eigen::Vector3d truth =
        head_turn_of(plane).to_model(Eigen::Vector3d(0, LipsPhantom::kFront - LipsPhantom::kSlitDepth, 0));
    // The profile's points 0.25 mm apart, the slit's bottom where the trilinear CT's threshold rounds it.
    EXPECT_LT((found->point - truth).norm(), 0.4) << "turned " << turn_degrees << ": found at "
                                                  << found->point.transpose() << ", the slit at " << truth.transpose();
  }
}

TEST(Stomion, NoneWhereTheLipsArePartedOverTheTeethOrShowNoSlit) {
  LipsPhantom parted;
  parted.parted = true;
  EXPECT_FALSE(stomion_of(parted, MidSagittalPlane{}));
  LipsPhantom smooth;  // the profile's rearmost points are its ends, the labralia
  smooth.slit = false;
  EXPECT_FALSE(stomion_of(smooth, MidSagittalPlane{}));
}

TEST(Stomion, PartedLipsGapIsHowFarApartTheLipsAreAndNoneWhereTheyMeet) {
  for (const double turn_degrees : {0.0, 15.0})
    for (const double gap : {6.0, 12.0}) {
      MidSagittalPlane plane;
      plane.turn = std::tan(turn_degrees * M_PI / 180);
      LipsPhantom parted;
      parted.parted = true;
      parted.gap = gap;
      // The gap's sharp edges ramp over a voxel of the phantom's 0.5 mm and of the front's 0.5 mm grid, where the rays
      // end at depths between the lips' and the teeth's.
      EXPECT_NEAR(gap_of(parted, plane), gap, 1.0) << "gap " << gap << ", turned " << turn_degrees;
      EXPECT_EQ(gap_of(LipsPhantom{}, plane), 0) << "closed lips, turned " << turn_degrees;
    }
  LipsPhantom smooth;
  smooth.slit = false;
  EXPECT_EQ(gap_of(smooth, MidSagittalPlane{}), 0);
}

// The real CTs: against the hand-placed stomion (tests/data/landmarks), read between the hand-placed labralia by the
// plane the segmentation finds.
double distance_from_placed(const std::string& ct_path, const std::string& placed_file, const MidSagittalPlane& plane) {
  const CtVolume ct = read_ct_volume(ct_path);
  std::map<std::string, Eigen::Vector3d> placed;
  for (const NamedLandmark& l : read_landmark_file(placed_file)) placed[l.name] = l.position;
  const std::optional<CtLandmark> found = find_stomion(ct.intensity, estimate_thresholds(ct.intensity).skin, plane,
                                                       placed.at("labrale superius"), placed.at("labrale inferius"));
  EXPECT_TRUE(found);
  return found ? (found->point - placed.at("stomion")).norm() : 1e9;
}

TEST(Stomion, VisibleHumanFemaleWithinTwoMillimetres) {
  const std::string ct = std::string(FACEHEX_SHARED_DIR) + "/data/ct/vhfemale-head.mha";
  if (!std::filesystem::exists(ct)) GTEST_SKIP() << "no shared data at " << ct;
  const MidSagittalPlane plane = testing::visible_human_plane();
  EXPECT_LE(distance_from_placed(ct, std::string(FACEHEX_TEST_DATA_DIR) + "/landmarks/vhfemale-head.json", plane), 2.0);
}

TEST(Stomion, BundledCtWithinThreeMillimetres) {
  MidSagittalPlane plane;  // as the segmentation finds it
  plane.x = 98.4;
  EXPECT_LE(distance_from_placed(default_ct(), std::string(FACEHEX_TEST_DATA_DIR) + "/landmarks/headsq.json", plane),
            3.0);
}

}  // namespace
}  // namespace facehex
