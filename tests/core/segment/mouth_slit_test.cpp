#include "core/segment/mouth_slit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <string>

#include "core/face/landmark_file.h"
#include "core/mesh/head_turn.h"
#include "core/segment/ct_volume.h"
#include "core/segment/thresholds.h"
#include "core/util/resources.h"
#include "tests/core/segment/phantom.h"

namespace facehex {
namespace {

// Closed lips in their head frame (plane x = 0, +y anterior, the stomion at z = 0): a front that curves back
// sideways and downwards, and the lips' slit along a mouth line that falls towards the corners, `depth` deep out to
// kCorner mm from the plane and ending there; the cheek beyond is smooth skin. The slit's upper wall is the upper lip
// turning in over it, kUpperWall tall; its lower wall slopes gently up the lower lip, kLowerWall tall.
struct MouthPhantom {
  static constexpr double kCorner = 25, kUpperWall = 0.75, kLowerWall = 2.25, kLineDrop = 0.004;
  double depth = 2;
  double scale = 1;  // the front's depth scaled about y = 0: a deeper (> 1) or shallower (< 1) face
  bool slit = true;
  // Lips apart instead of the slit: a gap `gap` tall at the plane around the mouth line, closing as an ellipse to the
  // corners, kGapDepth behind the lips.
  double gap = 0;
  static constexpr double kGapDepth = 12;

  static double line_z(double offset) { return -kLineDrop * offset * offset; }
  double front(double x, double z) const {
    const double offset = std::abs(x);
    double y = 20 - 0.012 * offset * offset - 0.02 * z * z;
    if (gap > 0) {
      const double half = offset < kCorner ? gap / 2 * std::sqrt(1 - offset * offset / (kCorner * kCorner)) : 0;
      return scale * (y - (std::abs(z - line_z(offset)) < half ? kGapDepth : 0));
    }
    if (slit && offset <= kCorner) {
      const double dz = z - line_z(offset);
      y -= std::max(0.0, depth * (1 - (dz > 0 ? dz / kUpperWall : -dz / kLowerWall)));
    }
    return scale * y;
  }
  // The corner in the head frame, side -1 right, +1 left: the middle of the upper wall, where the front recedes
  // fastest going down; where the lips are apart, the end of their gap.
  Eigen::Vector3d corner(int side) const {
    const double z = line_z(kCorner) + (gap > 0 ? 0 : kUpperWall / 2);
    return Eigen::Vector3d(side * kCorner, front(side * kCorner, z), z);
  }
  Eigen::Vector3d stomion() const { return Eigen::Vector3d(0, front(0, 0), 0); }
};

// The phantom seen through `plane`'s head frame, rolled by roll_degrees about the front-to-back axis through the
// stomion with the plane leaning with it.
struct PlacedPhantom {
  Field ct;
  MidSagittalPlane plane;
  std::array<Eigen::Vector3d, 2> corners;  // the model's frame
  Eigen::Vector3d stomion;
};

PlacedPhantom place(const MouthPhantom& face, double turn_degrees, double roll_degrees = 0) {
  PlacedPhantom p;
  const double c = std::cos(roll_degrees * M_PI / 180), s = std::sin(roll_degrees * M_PI / 180);
  p.plane.turn = std::tan(turn_degrees * M_PI / 180);
  p.plane.slope = s / c;
  p.plane.y = 10;
  // The roll about the head frame's y axis: upright (x, z) seen at (x c + z s, -x s + z c).
  const auto rolled = [&](const Eigen::Vector3d& upright) {
    return Eigen::Vector3d(upright.x() * c + upright.z() * s, upright.y(), -upright.x() * s + upright.z() * c);
  };
  const HeadTurn frame = head_turn_of(MidSagittalPlane{0, 0, 0, p.plane.turn, p.plane.y});
  p.ct =
      testing::face_front_phantom([&](double x, double z) { return face.front(x * c - z * s, x * s + z * c); }, frame);
  for (int side : {-1, 1}) p.corners[side < 0 ? 0 : 1] = frame.to_model(rolled(face.corner(side)));
  p.stomion = frame.to_model(rolled(face.stomion()));
  return p;
}

// Both corners found, not estimated, within `bound` mm of the phantom's.
void expect_corners(const MouthPhantom& face, double turn_degrees, double roll_degrees, double bound = 1.0) {
  const PlacedPhantom p = place(face, turn_degrees, roll_degrees);
  const MouthCorners found = find_mouth_corners(p.ct, 0, p.plane, p.stomion);
  const std::string context =
      " (turned " + std::to_string(turn_degrees) + ", rolled " + std::to_string(roll_degrees) + ")";
  for (int c = 0; c < 2; ++c) {
    ASSERT_TRUE(found[c]) << kMouthCornerNames[c] << context;
    EXPECT_FALSE(found[c]->estimated);
    EXPECT_LT((found[c]->point - p.corners[c]).norm(), bound)
        << kMouthCornerNames[c] << context << ": found at " << found[c]->point.transpose() << ", the corner is at "
        << p.corners[c].transpose();
  }
}

TEST(MouthSlit, TheEndsOfTheClosedLipsSlitUprightAndTurned) {
  for (const double turn : {0.0, 12.0, -18.0}) expect_corners(MouthPhantom{}, turn, 0);
}

TEST(MouthSlit, TheEndsOfAShallowerSlitOnAShallowerFace) {
  // The end is read against the slit's own depth: a slit about half as deep on a face 8 % shallower (a notch under 1
  // mm, shallower throughout than half the default slit's) ends where it ends.
  MouthPhantom face;
  face.depth = 1.1;
  face.scale = 0.92;
  expect_corners(face, 0, 0);
}

TEST(MouthSlit, TheEndsOfTheSlitOnAHeadTiltedTowardsAShoulder) {
  // Rolled 15 degrees, one corner lies 13 mm above the other: the line is followed along the stomion's line across
  // the leaning plane, not level.
  for (const double roll : {15.0, -15.0}) expect_corners(MouthPhantom{}, 0, roll);
}

TEST(MouthSlit, NoneWithoutASlitOrOnCoarseVoxels) {
  MouthPhantom smooth;
  smooth.slit = false;
  const PlacedPhantom p = place(smooth, 0);
  const MouthCorners none = find_mouth_corners(p.ct, 0, p.plane, p.stomion);
  EXPECT_FALSE(none[0]);
  EXPECT_FALSE(none[1]);
  // The same lips on 2 mm voxels: a slit 3 mm tall is then a voxel's partial volume.
  const PlacedPhantom fine = place(MouthPhantom{}, 0);
  GridGeometry coarse = fine.ct.geometry;
  coarse.spacing = Eigen::Vector3d::Constant(2.0);
  for (int a = 0; a < 3; ++a) coarse.dims[a] = (fine.ct.geometry.dims[a] - 1) / 4 + 1;
  const MouthCorners on_coarse = find_mouth_corners(resample(fine.ct, coarse), 0, fine.plane, fine.stomion);
  EXPECT_FALSE(on_coarse[0]);
  EXPECT_FALSE(on_coarse[1]);
}

TEST(MouthSlit, AnOpenMouthsCornersAreWhereTheGapBetweenTheLipsEnds) {
  for (const double gap : {6.0, 12.0})
    for (const double turn : {0.0, 12.0}) {
      MouthPhantom face;
      face.gap = gap;
      const PlacedPhantom p = place(face, turn);
      // The lips' fronts above and below the gap, as the profile finds them.
      const HeadTurn frame = head_turn_of(p.plane);
      const auto lip = [&](double z) { return frame.to_model(Eigen::Vector3d(0, face.front(0, z), z)); };
      const MouthCorners found = find_open_mouth_corners(p.ct, 0, p.plane, lip(gap / 2 + 2), lip(-gap / 2 - 2));
      const std::string context = " (gap " + std::to_string(gap) + ", turned " + std::to_string(turn) + ")";
      for (int c = 0; c < 2; ++c) {
        ASSERT_TRUE(found[c]) << kMouthCornerNames[c] << context;
        // Across the face (x and z of the head frame): the running mean's 2 mm and the gap's last half millimetre.
        const Eigen::Vector3d at = frame.to_head(found[c]->point), truth = frame.to_head(p.corners[c]);
        EXPECT_LT(std::hypot(at.x() - truth.x(), at.z() - truth.z()), 1.5)
            << kMouthCornerNames[c] << context << ": found at " << at.transpose() << ", the corner at "
            << truth.transpose();
      }
      // Closed lips have no gap whose end is a corner.
      const PlacedPhantom closed = place(MouthPhantom{}, turn);
      const MouthCorners none =
          find_open_mouth_corners(closed.ct, 0, closed.plane, lip(gap / 2 + 2), lip(-gap / 2 - 2));
      EXPECT_FALSE(none[0]) << context;
      EXPECT_FALSE(none[1]) << context;
    }
}

// The real CT: the corners against the hand-placed ones (tests/data/landmarks), read by the plane the segmentation
// finds and the hand-placed stomion; on its own 1 mm voxels, on 1.5 mm slices (the coarsest read) and on 3 mm slices
// (none: the skin's corners stand).
TEST(MouthSlit, VisibleHumanFemaleNearTheHandPlacedOnesAndNoneOnThickSlices) {
  const std::string path = std::string(FACEHEX_SHARED_DIR) + "/data/ct/vhfemale-head.mha";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no shared data at " << path;
  const CtVolume ct = read_ct_volume(path);
  std::map<std::string, NamedLandmark> placed;
  for (const NamedLandmark& l :
       read_landmark_file(std::string(FACEHEX_TEST_DATA_DIR) + "/landmarks/vhfemale-head.json"))
    placed[l.name] = l;
  const double skin = estimate_thresholds(ct.intensity).skin;
  const auto corners_on_slices = [&](double thickness) {
    GridGeometry thick = ct.intensity.geometry;
    thick.spacing.z() = thickness;
    thick.dims[2] = static_cast<int>((ct.intensity.geometry.dims[2] - 1) / thickness) + 1;
    return find_mouth_corners(thickness == 1 ? ct.intensity : resample(ct.intensity, thick), skin,
                              testing::visible_human_plane(), placed.at("stomion").position);
  };
  for (const double thickness : {1.0, 1.5}) {
    const MouthCorners found = corners_on_slices(thickness);
    for (int c = 0; c < 2; ++c) {
      const NamedLandmark& ref = placed.at(kMouthCornerNames[c]);
      ASSERT_TRUE(found[c]) << ref.name << " on " << thickness << " mm slices";
      EXPECT_LE((found[c]->point - ref.position).norm(), 2.0)
          << ref.name << " on " << thickness << " mm slices found at " << found[c]->point.transpose() << ", placed at "
          << ref.position.transpose();
    }
  }
  const MouthCorners on_thick = corners_on_slices(3);
  EXPECT_FALSE(on_thick[0] || on_thick[1]);
}

}  // namespace
}  // namespace facehex
