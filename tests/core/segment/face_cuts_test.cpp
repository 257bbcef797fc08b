#include "core/segment/face_cuts.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "core/segment/morphology.h"
#include "core/segment/soft_tissue.h"
#include "core/util/error.h"

namespace facehex {
namespace {

// A 2 mm grid over [0, 120] x [0, 120] x [0, 180] mm (voxel centres), +y anterior, +z superior.
GridGeometry grid(double height = 180) {
  GridGeometry g;
  g.spacing = Eigen::Vector3d::Constant(2.0);
  g.dims = {61, 61, static_cast<int>(std::lround(height / 2)) + 1};
  return g;
}

// Sets every voxel whose centre lies in the closed box [lo, hi].
void fill(Mask& m, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const GridGeometry& g = m.geometry;
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const Eigen::Vector3d p = g.point(i, j, k);
        if ((p.array() >= lo.array()).all() && (p.array() <= hi.array()).all()) m(i, j, k) = 1;
      }
}

// The synthetic head, symmetric about x = 60, in its own frame (y anterior, z superior): a block x in [20, 100],
// y in [20, 90], z in [10, 170], its front rounded (y <= 90 - (x - 60)^2 / 80); a nose x in [56, 64] reaching y = 104
// over z in [90, 110] (a flat front, as a field-of-view cut leaves it); a brow and forehead y in [90, 92] above z =
// 130; ears x in [10, 110] at y in [57, 60] (thin, as an auricle is), z in [100, 120]; shoulders x in [0, 120], y in
// [30, 80], z below 8; the chin's bone x in [54, 66], y in [76, 86], z in [40, 50]. Known anatomy: pronasale z 100,
// nasion the middle of the flat y = 90 over z in [116, 132], z 124; glabella the middle of the brow, z 140; menton z
// 40; ears' front y 60. Known cuts with the default options: centre_x 60, bottom 40 - 15 = 25, top 140 + 15 = 155,
// posterior 60 + 12 = 72. `pose` maps the head's frame into the CT's (a rotation about the point (60, 60, 90)), then
// `lift` moves it up.
struct Head {
  Mask head, bone;
  explicit Head(const Eigen::Matrix3d& pose = Eigen::Matrix3d::Identity(), bool shoulders = true, double lift = 0)
      : head(grid(), 0), bone(grid(), 0) {
    const Eigen::Vector3d pivot(60, 60, 90);
    const GridGeometry& g = head.geometry;
    auto in = [](const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
      return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
    };
    for (int k = 0; k < g.dims[2]; ++k)
      for (int j = 0; j < g.dims[1]; ++j)
        for (int i = 0; i < g.dims[0]; ++i) {
          const Eigen::Vector3d p = pivot + pose.transpose() * (g.point(i, j, k) - Eigen::Vector3d(0, 0, lift) - pivot);
          const bool rounded = p.y() <= 90 - (p.x() - 60) * (p.x() - 60) / 80;
          head(i, j, k) = (rounded && in(p, {20, 20, 10}, {100, 90, 170})) || in(p, {56, 90, 90}, {64, 104, 110}) ||
                          (p.y() <= 94 - (p.z() - 140) * (p.z() - 140) / 25 && in(p, {30, 90, 130}, {90, 94, 150})) ||
                          in(p, {30, 90, 150}, {90, 92, 170}) || in(p, {10, 57, 100}, {110, 60, 120}) ||
                          (shoulders && in(p, {0, 30, 0}, {120, 80, 8}));
          bone(i, j, k) = in(p, {54, 76, 40}, {66, 86, 50});
        }
  }
};

Eigen::Matrix3d rotation(double degrees, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(degrees * M_PI / 180, axis.normalized()).toRotationMatrix();
}

// The cuts as the segmentation finds them (core/segment/soft_tissue.cpp): the head without its ears is the head opened.
FaceCuts cuts_of(const Mask& head, const Mask& bone, const FaceCutOptions& options) {
  return find_face_cuts(head, open(head, SegmentOptions().opening_radius), bone, options);
}

void expect_error(const std::function<void()>& run, const std::string& words) {
  try {
    run();
    ADD_FAILURE() << "expected facehex::Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.subject(), "segment") << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << "'" << e.what() << "' lacks '" << words << "'";
  }
}

TEST(FaceCuts, AutomaticCutsOfASyntheticHeadFollowItsAnatomy) {
  const Head h;
  const FaceCuts cuts = cuts_of(h.head, h.bone, FaceCutOptions());
  ASSERT_TRUE(cuts.anatomy);
  const FaceAnatomy& a = *cuts.anatomy;
  EXPECT_NEAR(a.centre_x, 60, 1e-9);
  EXPECT_NEAR(a.roll_degrees, 0, 1e-9);
  EXPECT_TRUE(a.pronasale.isApprox(Eigen::Vector3d(60, 104, 100))) << a.pronasale.transpose();
  EXPECT_TRUE(a.nose_clipped);
  EXPECT_NEAR(a.nasion.x(), 60, 1e-9);
  EXPECT_NEAR(a.nasion.y(), 90, 1e-9);
  EXPECT_NEAR(a.nasion.z(), 124, 2.0);
  EXPECT_TRUE(a.glabella.isApprox(Eigen::Vector3d(60, 94, 140))) << a.glabella.transpose();
  // The chin's lowest level is a plate 12 mm wide: the menton is its point on the plane, at its front.
  EXPECT_TRUE(a.menton.isApprox(Eigen::Vector3d(60, 86, 40))) << a.menton.transpose();
  EXPECT_NEAR(a.ear_front_y, 60, 1e-9);
  EXPECT_NEAR(a.lowest_head_z, 10, 1e-9);  // the shoulders (z <= 8) are not head
  EXPECT_NEAR(cuts.centre_x, 60, 1e-9);
  EXPECT_NEAR(cuts.bottom_z, 25, 1e-9);
  EXPECT_NEAR(cuts.top_z, 155, 1e-9);
  // Its ears are thin plates with no hollow: no tragus is seen, and the posterior cut keeps its clearance from where a
  // tragus would lie, 3 mm in front of the auricle's front edge.
  EXPECT_FALSE(a.tragi[0] || a.tragi[1]);
  EXPECT_NEAR(cuts.posterior_y, 60 + 3 + 9, 1e-9);
  EXPECT_EQ(cuts.jaw_z, -std::numeric_limits<double>::infinity());  // find_jaw_cut's business
  EXPECT_NE(face_anatomy_text(a).find("glabella (60.0, 94.0, 140.0)"), std::string::npos) << face_anatomy_text(a);
}

TEST(FaceCuts, TheClearancesAreOptions) {
  const Head h;
  FaceCutOptions o;
  o.chin_clearance = 4;
  o.ear_clearance = 6;
  o.brow_clearance = 9;
  const FaceCuts cuts = cuts_of(h.head, h.bone, o);
  EXPECT_NEAR(cuts.bottom_z, 36, 1e-9);
  EXPECT_NEAR(cuts.top_z, 149, 1e-9);
  EXPECT_NEAR(cuts.posterior_y, 60 + 3 + 6, 1e-9);
}

TEST(FaceCuts, TheFrontOfTheEarsIsTheMoreAnteriorTragusFound) {
  FaceAnatomy a;
  a.ear_front_y = 60;
  EXPECT_NEAR(front_of_the_ears(a), 63, 1e-9);  // no tragus: where one would lie
  a.tragi[0] = CtLandmark{Eigen::Vector3d(-70, 64.5, 90), false};
  a.tragi[1] = CtLandmark{Eigen::Vector3d(70, 61.5, 90), false};
  EXPECT_NEAR(front_of_the_ears(a), 64.5, 1e-9);
  a.tragi[0]->estimated = true;  // placed where no auricle stood out: not a tragus seen
  EXPECT_NEAR(front_of_the_ears(a), 61.5, 1e-9);
}

TEST(FaceCuts, TheEarsLineRunsThroughBothEars) {
  FaceAnatomy a;
  a.ear_front_y = 60;
  a.ear_fronts_y = {60, 52};
  const auto expect_line = [](const EarsLine& line, double y_at_centre, double slope, const char* what) {
    EXPECT_NEAR(line.y_at_centre, y_at_centre, 1e-9) << what;
    EXPECT_NEAR(line.slope, slope, 1e-12) << what;
  };
  // No tragus: coronal, where the more anterior one would lie.
  expect_line(ears_line(a, 0), 63, 0, "no tragus");
  // Both tragi: through them (10 mm apart in y over 140 mm in x).
  a.tragi[0] = CtLandmark{Eigen::Vector3d(-70, 64, 90), false};
  a.tragi[1] = CtLandmark{Eigen::Vector3d(70, 54, 92), false};
  expect_line(ears_line(a, 0), 59, -10.0 / 140, "both tragi");
  expect_line(ears_line(a, 7), 58.5, -10.0 / 140, "both tragi, the plane at x 7");
  // One tragus: the other side's point at its mirror image's x, 3 mm in front of that side's auricle edge.
  a.tragi[1].reset();
  expect_line(ears_line(a, 0), 0.5 * (64 + 55), -9.0 / 140, "the right tragus and the left auricle");
  a.tragi[1] = CtLandmark{Eigen::Vector3d(70, 54, 92), true};  // estimated: no tragus seen
  expect_line(ears_line(a, 0), 0.5 * (64 + 55), -9.0 / 140, "an estimated left tragus");
  // Without an auricle seen on the other side, or with the auricles estimated (none stood out): coronal.
  a.ear_fronts_y[1] = -std::numeric_limits<double>::infinity();
  expect_line(ears_line(a, 0), 64, 0, "no left auricle");
  a.ear_fronts_y[1] = 52;
  a.ears_estimated = true;
  expect_line(ears_line(a, 0), 64, 0, "auricles estimated");
  // Tragi whose line turns more than kMaxPosteriorCutTurn: coronal in front of the more anterior.
  a.ears_estimated = false;
  const double too_far = 140 * std::tan((kMaxPosteriorCutTurn + 0.5) * M_PI / 180);
  a.tragi[1] = CtLandmark{Eigen::Vector3d(70, 64 - too_far, 92), false};
  expect_line(ears_line(a, 0), 64, 0, "turned too far");
  a.tragi[1] = CtLandmark{Eigen::Vector3d(70, 64 - too_far + 2, 92), false};
  EXPECT_LT(ears_line(a, 0).slope, 0);
}

TEST(FaceCuts, TheMentonIsTheLowestBoneConnectedToTheChinNearTheSkin) {
  Head h;
  // Lower bone reached from the chin within the mid-plane band: the mandible's lower border curving back 20 mm.
  fill(h.bone, {58, 66, 30}, {62, 78, 40});
  EXPECT_NEAR(cuts_of(h.head, h.bone, FaceCutOptions()).anatomy->menton.z(), 30, 1e-9);
  // Bone lower still but not connected (the hyoid), or behind the reach (the spine), or lateral: not the chin.
  fill(h.bone, {58, 50, 14}, {62, 60, 26});
  fill(h.bone, {58, 30, 12}, {62, 40, 60});
  fill(h.bone, {76, 80, 20}, {78, 86, 40});
  EXPECT_NEAR(cuts_of(h.head, h.bone, FaceCutOptions()).anatomy->menton.z(), 30, 1e-9);
  // Without the chin's bone near the skin, the error names the option that places the bottom cut.
  Head no_chin;
  no_chin.bone = Mask(no_chin.head.geometry, 0);
  fill(no_chin.bone, {54, 50, 40}, {66, 60, 50});  // 30 mm behind the skin
  expect_error([&] { cuts_of(no_chin.head, no_chin.bone, FaceCutOptions()); }, "--bottom-cut");
}

// Lips apart further than kChinGap: the maxilla and upper teeth reach below the chin search's start (30 mm below the
// pronasale) and make a short run there, 14 mm above the chin's bone; the chin's run is the taller one.
TEST(FaceCuts, TheChinIsTheTallestRunOfBoneNearTheSkinNotTheTeethAboveIt) {
  Head h;
  fill(h.bone, {54, 80, 114}, {66, 86, 158});  // the nasal and frontal bones above the nasal aperture
  fill(h.bone, {54, 76, 64}, {66, 86, 86});    // the maxilla and upper teeth below it, down to z = 64
  const FaceCuts cuts = cuts_of(h.head, h.bone, FaceCutOptions());
  ASSERT_TRUE(cuts.anatomy);
  EXPECT_NEAR(cuts.anatomy->menton.z(), 40, 1e-9);
  EXPECT_NEAR(cuts.bottom_z, 25, 1e-9);
}

// A field of view that cuts the face flat can leave the forehead as far forward as the nose (or further, when the cut
// is slanted): the nose is the most anterior point in front of the nasal aperture, the highest run of levels without
// bone near the skin.
TEST(FaceCuts, TheNoseIsInFrontOfTheNasalAperture) {
  Head h;
  fill(h.head, {30, 90, 152}, {90, 106, 170});  // a forehead out to y = 106, in front of the nose's 104
  fill(h.bone, {54, 80, 114}, {66, 86, 158});   // the frontal and nasal bones behind it, the scalp above without
  fill(h.bone, {54, 76, 56}, {66, 86, 86});     // the maxilla and teeth below the aperture
  const FaceCuts cuts = cuts_of(h.head, h.bone, FaceCutOptions());
  ASSERT_TRUE(cuts.anatomy);
  EXPECT_NEAR(cuts.anatomy->pronasale.z(), 100, 2.0) << cuts.anatomy->pronasale.transpose();
  EXPECT_NEAR(cuts.anatomy->pronasale.y(), 104, 1e-9);
  // The chin's run goes down from the teeth over the 6 mm between them and the chin's bone (lips apart).
  EXPECT_NEAR(cuts.anatomy->menton.z(), 40, 1e-9);
}

TEST(FaceCuts, ATiltedHeadKeepsItsMidPlaneAndLandmarks) {
  // Tilted 15 degrees towards a shoulder (about the y axis): the plane's trace leans by 15 degrees.
  const Head h(rotation(15, Eigen::Vector3d::UnitY()), false);
  const FaceAnatomy a = *cuts_of(h.head, h.bone, FaceCutOptions()).anatomy;
  EXPECT_NEAR(std::abs(a.roll_degrees), 15, 2.0);
  // The pronasale of the tilted head: (60, 104, 100) rotated about (60, 60, 90).
  const Eigen::Vector3d prn =
      Eigen::Vector3d(60, 60, 90) + rotation(15, Eigen::Vector3d::UnitY()) * Eigen::Vector3d(0, 44, 10);
  EXPECT_NEAR(a.centre_at(prn.z()), prn.x(), 2.0);
  EXPECT_NEAR(a.pronasale.y(), prn.y(), 2.0);
  // The landmarks are read on the leaning plane; on an upright head, and on a plane given, on the vertical.
  const FaceCuts tilted = cuts_of(h.head, h.bone, FaceCutOptions());
  const MidSagittalPlane plane = landmark_plane(tilted, FaceCutOptions());
  EXPECT_EQ(plane.slope, tilted.anatomy->roll_slope);
  EXPECT_NEAR(plane.x_at(prn.y(), prn.z()), prn.x(), 2.0);
  // Tragi found level contradict the lean: the head is upright and the plane vertical. Tragi tilted with the head (the
  // right one higher when the plane's top leans to +x) agree with it, and so does a pair with one estimated.
  const auto with_tragi = [&](double right_z, double left_z, bool estimated) {
    FaceCuts cuts = tilted;
    cuts.anatomy->tragi = {CtLandmark{Eigen::Vector3d(0, 60, right_z), estimated},
                           CtLandmark{Eigen::Vector3d(120, 60, left_z), false}};
    return landmark_plane(cuts, FaceCutOptions());
  };
  EXPECT_EQ(with_tragi(90, 90, false).slope, 0.0);
  EXPECT_EQ(with_tragi(90, 90, false).x, tilted.centre_x);
  const double rise = 120 * std::tan(tilted.anatomy->roll_degrees * M_PI / 180);
  EXPECT_EQ(with_tragi(90 + rise / 2, 90 - rise / 2, false).slope, tilted.anatomy->roll_slope);
  EXPECT_EQ(with_tragi(90 - rise / 2, 90 + rise / 2, false).slope, 0.0);  // tilted the other way
  EXPECT_EQ(with_tragi(90, 90, true).slope, tilted.anatomy->roll_slope);
  // Without the tragi, the lean is taken when most levels agree with it (as on this phantom), not when only half do
  // and the head's 3D mirror plane (leaning with the phantom) is not known.
  EXPECT_GE(tilted.anatomy->roll_support, kLandmarkPlaneLeanSupport);
  EXPECT_NEAR(tilted.anatomy->mirror_roll_degrees, tilted.anatomy->roll_degrees, 1.0);
  FaceCuts weak = tilted;
  weak.anatomy->roll_support = 0.5;
  weak.anatomy->mirror_roll_degrees = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(landmark_plane(weak, FaceCutOptions()).slope, 0.0);
  EXPECT_EQ(landmark_plane(weak, FaceCutOptions()).x, weak.centre_x);
  // Half the levels, but the head's 3D mirror plane leaning with the fit: taken; leaning the other way: not.
  weak.anatomy->mirror_roll_degrees = weak.anatomy->roll_degrees + 4;
  EXPECT_EQ(landmark_plane(weak, FaceCutOptions()).slope, weak.anatomy->roll_slope);
  weak.anatomy->mirror_roll_degrees = -weak.anatomy->roll_degrees;
  EXPECT_EQ(landmark_plane(weak, FaceCutOptions()).slope, 0.0);
  const Head upright(Eigen::Matrix3d::Identity(), false);
  const FaceCuts straight = cuts_of(upright.head, upright.bone, FaceCutOptions());
  EXPECT_EQ(landmark_plane(straight, FaceCutOptions()).slope, 0.0);
  EXPECT_EQ(landmark_plane(straight, FaceCutOptions()).x, straight.centre_x);
  FaceCutOptions given;
  given.centre_x = 61.0;
  EXPECT_EQ(landmark_plane(cuts_of(h.head, h.bone, given), given).slope, 0.0);
}

TEST(FaceCuts, ATiltedHeadsBottomCutIsPerpendicularToItsPlaneAndLeavesItsShouldersOut) {
  // Tilted 20 degrees with its shoulders (z below 8 in its own frame, 32 mm under the menton), the chin's clearance
  // 25 mm: the bottom cut tilts with the head, 25 mm under the menton, and cuts away every shoulder voxel; a level cut
  // through the same point leaves the raised shoulder in the region. The top cut would tilt too, 15 mm above the
  // glabella, but the phantom's forehead ends 15 mm above it on the side the tilt lowers, under where the tilted cut
  // would run on the other: it stays level there. Upright, both stay level; given, they are level.
  const Eigen::Matrix3d pose = rotation(20, Eigen::Vector3d::UnitY());
  const Head h(pose, true);
  FaceCutOptions options;
  options.chin_clearance = 25;
  const FaceCuts cuts = cuts_of(h.head, h.bone, options);
  EXPECT_NEAR(std::atan(cuts.bottom_slope) * 180 / M_PI, -cuts.anatomy->roll_degrees, 1e-9);
  EXPECT_NEAR(std::abs(std::atan(cuts.bottom_slope) * 180 / M_PI), 20, 2.0);
  const Eigen::Vector3d& menton = cuts.anatomy->menton;
  EXPECT_NEAR(menton.z() - cuts.bottom_z_at(menton.x()), 25, 1e-9);
  EXPECT_EQ(cuts.top_slope, 0.0);
  EXPECT_LE(cuts.top_z, cuts.anatomy->glabella.z() + 15);
  const CutPlane bottom = cuts.planes()[1];
  ASSERT_EQ(bottom.side, V0);
  FaceCuts level = cuts;
  level.bottom_slope = 0;
  level.bottom_z = cuts.bottom_z_at(menton.x());
  const Eigen::Vector3d pivot(60, 60, 90);
  int shoulder_voxels = 0, left_by_level = 0;
  const GridGeometry& g = h.head.geometry;
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const Eigen::Vector3d p = g.point(i, j, k);
        if (!h.head(i, j, k) || (pivot + pose.transpose() * (p - pivot)).z() > 8) continue;
        ++shoulder_voxels;
        EXPECT_GT(bottom.distance(p), 0) << p.transpose();
        left_by_level += level.planes()[1].distance(p) <= 0;
      }
  EXPECT_GT(shoulder_voxels, 100);
  EXPECT_GT(left_by_level, 0);
  const Head upright(Eigen::Matrix3d::Identity(), true);
  const FaceCuts straight = cuts_of(upright.head, upright.bone, options);
  EXPECT_EQ(straight.bottom_slope, 0.0);
  EXPECT_EQ(straight.top_slope, 0.0);
  FaceCutOptions given = options;
  given.bottom_z = 20;
  given.top_z = 150;
  const FaceCuts as_given = cuts_of(h.head, h.bone, given);
  EXPECT_EQ(as_given.bottom_slope, 0.0);
  EXPECT_EQ(as_given.top_slope, 0.0);
}

// Tilted 30 degrees, beyond any head in a scanner (a symmetry fit that leans so far has read the face wrongly): an
// error naming the angle and the options that place the cuts by hand, not a model cut along a wrong plane.
TEST(FaceCuts, APlaneLeaningBeyondTwentyFiveDegreesIsRefused) {
  const Head h(rotation(30, Eigen::Vector3d::UnitY()), false);
  try {
    cuts_of(h.head, h.bone, FaceCutOptions());
    ADD_FAILURE() << "a 30-degree roll was accepted";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("mid-sagittal plane leaning"), std::string::npos) << what;
    EXPECT_NE(what.find("beyond the 25.0"), std::string::npos) << what;
    EXPECT_NE(what.find("--mid-plane"), std::string::npos) << what;
  }
}

TEST(FaceCuts, ATurnedHeadKeepsItsMidPlaneNearTheNose) {
  for (const double degrees : {-15.0, 10.0, 15.0}) {
    const Eigen::Matrix3d pose = rotation(degrees, Eigen::Vector3d::UnitZ());
    const Head h(pose, false);
    const FaceCuts cuts = cuts_of(h.head, h.bone, FaceCutOptions());
    const Eigen::Vector3d prn = Eigen::Vector3d(60, 60, 90) + pose * Eigen::Vector3d(0, 44, 10);
    EXPECT_NEAR(cuts.centre_x, prn.x(), 5.0) << degrees;
    EXPECT_NEAR(cuts.anatomy->menton.z(), 40, 2.0) << degrees;
    EXPECT_NEAR(cuts.top_z, 155, 5.0) << degrees << ": " << face_anatomy_text(*cuts.anatomy);
  }
}

// A nearly flat face whose field of view cut the nose into a plateau running up the forehead (no nasion hollow), the
// nose 10 mm in front of the cheeks 40 mm to either side: turned 10 degrees about the vertical, one cheek comes within
// 4 mm of the nose. The two cheeks' mean still leaves the nose standing out, so it is a head, not a box.
TEST(FaceCuts, ATurnedHeadWithAFlatClippedFaceIsAHead) {
  const Eigen::Vector3d pivot(60, 60, 90);
  const Eigen::Matrix3d pose = rotation(10, Eigen::Vector3d::UnitZ());
  Mask head(grid(), 0), bone(grid(), 0);
  const GridGeometry& g = head.geometry;
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const Eigen::Vector3d p = pivot + pose.transpose() * (g.point(i, j, k) - pivot);
        const auto in = [&](const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
          return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
        };
        const bool front = p.y() <= 90 - (p.x() - 60) * (p.x() - 60) / 400;  // cheeks 4 mm behind at 40 mm
        head(i, j, k) = (front && in({6, 20, 10}, {114, 90, 170})) || in({56, 90, 80}, {64, 96, 170});
        bone(i, j, k) = in({54, 76, 40}, {66, 86, 50});
      }
  const FaceCuts cuts = cuts_of(head, bone, FaceCutOptions());
  ASSERT_TRUE(cuts.anatomy);
  EXPECT_NEAR(cuts.anatomy->menton.z(), 40, 2.0);
  // No auricle stands out of this head: its ears' front is estimated where it is widest, and the summary says so.
  EXPECT_TRUE(cuts.anatomy->ears_estimated);
  EXPECT_NE(face_anatomy_text(*cuts.anatomy).find("estimated: no auricle stands out"), std::string::npos);
}

TEST(FaceCuts, CutsStayInsideTheCt) {
  // 30 mm lower, the menton is at z = 10 and 10 - 15 lies below the CT: the bottom cut stays border_margin inside.
  const Head low(Eigen::Matrix3d::Identity(), false, -30);
  FaceCutOptions o;
  EXPECT_NEAR(cuts_of(low.head, low.bone, o).bottom_z, 3, 1e-9);
  o.border_margin = 5;
  EXPECT_NEAR(cuts_of(low.head, low.bone, o).bottom_z, 5, 1e-9);
  // 20 mm higher, the glabella is at z = 160 and 160 + 25 lies above the CT (z <= 180).
  const Head high(Eigen::Matrix3d::Identity(), false, 20);
  o = FaceCutOptions();
  o.brow_clearance = 25;
  EXPECT_NEAR(cuts_of(high.head, high.bone, o).top_z, 177, 1e-9);
}

// Clears the masks above z = top, the highest level rounded off (its front 6 mm back), as a scan that ends there
// leaves them.
void end_scan_at(Head& h, double top) {
  const GridGeometry& g = h.head.geometry;
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const Eigen::Vector3d p = g.point(i, j, k);
        if (p.z() > top || (p.z() == top && p.y() > 84)) h.head(i, j, k) = h.bone(i, j, k) = 0;
      }
}

TEST(FaceCuts, AScanEndingInTheForeheadKeepsTheTopCutInsideTheHead) {
  // Ending 2 mm above the middle of the nasion's hollow: its rounded top level is not the nasion.
  Head h;
  end_scan_at(h, 126);
  FaceCuts cuts = cuts_of(h.head, h.bone, FaceCutOptions());
  ASSERT_TRUE(cuts.anatomy);
  EXPECT_NEAR(cuts.anatomy->nasion.y(), 90, 1e-9);
  EXPECT_GE(cuts.anatomy->nasion.z(), 116);
  EXPECT_LE(cuts.anatomy->nasion.z(), 122);
  EXPECT_NEAR(cuts.anatomy->highest_head_z, 126, 1e-9);
  EXPECT_NEAR(cuts.top_z, 123, 1e-9);  // the head's top less border_margin, below glabella + brow_clearance
  // Ending within the hollow: nothing above the nasion is left for the glabella; the top cut is the head's top.
  Head low;
  end_scan_at(low, 120);
  cuts = cuts_of(low.head, low.bone, FaceCutOptions());
  ASSERT_TRUE(cuts.anatomy);
  EXPECT_TRUE(cuts.anatomy->brow_unseen);
  EXPECT_NEAR(cuts.top_z, 117, 1e-9);
  EXPECT_NE(face_anatomy_text(*cuts.anatomy).find("no nasion below a brow"), std::string::npos);
  // A whole head is not flagged.
  const Head whole;
  const FaceCuts whole_cuts = cuts_of(whole.head, whole.bone, FaceCutOptions());
  ASSERT_TRUE(whole_cuts.anatomy);
  EXPECT_FALSE(whole_cuts.anatomy->brow_unseen);
}

// Clears the masks where `cut` holds, as a scan that ends there leaves them.
void clear_where(Head& h, const std::function<bool(const Eigen::Vector3d&)>& cut) {
  const GridGeometry& g = h.head.geometry;
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i)
        if (cut(g.point(i, j, k))) h.head(i, j, k) = h.bone(i, j, k) = 0;
}

TEST(FaceCuts, AScanEndingAcrossTheForeheadTiltedKeepsTheTopCutBelowTheForeheadsFront) {
  // The scan's end leans 5 degrees against the head, rising backwards from z 150 at the forehead's front (y 92): the
  // head's highest level is 156 at its back, and a top cut there less border_margin would leave the front of the
  // forehead ending in the scan's tilted end instead of the cut.
  const double lean = std::tan(5 * M_PI / 180);
  Head tilted;
  clear_where(tilted, [&](const Eigen::Vector3d& p) { return p.z() > 150 + (92 - p.y()) * lean; });
  const FaceCuts cuts = cuts_of(tilted.head, tilted.bone, FaceCutOptions());
  ASSERT_TRUE(cuts.anatomy);
  EXPECT_NEAR(cuts.anatomy->highest_head_z, 156, 1e-9);
  EXPECT_NEAR(cuts.anatomy->forehead_end_z, 150, 1e-9);
  EXPECT_NEAR(cuts.top_z, 147, 1e-9);  // below the forehead's front by border_margin
  EXPECT_NE(face_anatomy_text(*cuts.anatomy).find("the forehead's front whole up to z 150.0"), std::string::npos)
      << face_anatomy_text(*cuts.anatomy);
  // A forehead that recedes as steeply as one does (45 degrees from z 150) is whole up to the head's top, and so is
  // the untouched head: their top cuts stay 15 mm above the glabella.
  Head receding;
  clear_where(receding, [](const Eigen::Vector3d& p) { return p.z() > 150 && p.y() > 92 - (p.z() - 150); });
  const Head whole;
  for (const Head* h : std::vector<const Head*>{&receding, &whole}) {
    const FaceCuts c = cuts_of(h->head, h->bone, FaceCutOptions());
    ASSERT_TRUE(c.anatomy);
    EXPECT_GE(c.anatomy->forehead_end_z, 170);
    EXPECT_NEAR(c.top_z, 155, 1e-9);
  }
}

TEST(FaceCuts, AScanEndingAcrossTheFaceRegionTiltedToTheBackKeepsTheTopCutBelowIt) {
  // The scan's end leans 10 degrees down to the back from z 158 at the forehead's front (y 92): the front is whole up
  // to the top cut 15 mm above the glabella (155), but the end crosses the face region (in front of the posterior
  // cut, y 72) from z 154.5 at the cut: its section loses a wedge level by level above that, and the top cut stays
  // border_margin below the last level where it is whole.
  const double lean = std::tan(10 * M_PI / 180);
  Head tilted;
  clear_where(tilted, [&](const Eigen::Vector3d& p) { return p.z() > 158 + (p.y() - 92) * lean; });
  const FaceCuts cuts = cuts_of(tilted.head, tilted.bone, FaceCutOptions());
  ASSERT_TRUE(cuts.anatomy);
  EXPECT_NEAR(cuts.posterior_y, 72, 1e-9);
  EXPECT_GE(cuts.anatomy->forehead_end_z, 158);  // the front is whole
  EXPECT_NEAR(cuts.section_end_z, 154, 1e-9);
  EXPECT_NEAR(cuts.top_z, 151, 1e-9);
  // The untouched head's section is whole up to its top (z 170).
  const Head whole;
  EXPECT_GE(cuts_of(whole.head, whole.bone, FaceCutOptions()).section_end_z, 170);
}

TEST(FaceCuts, AScanStartingWithinTheChinKeepsTheBottomCutInsideTheBody) {
  // Air below z = 30 (a field of view that starts within the chin, or a volume resampled into a larger box): the
  // menton's rule would cut at 25, below the body, leaving the model no bottom side.
  Head h;
  const GridGeometry& g = h.head.geometry;
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i)
        if (g.point(i, j, k).z() < 30) h.head(i, j, k) = h.bone(i, j, k) = 0;
  const FaceCuts cuts = cuts_of(h.head, h.bone, FaceCutOptions());
  ASSERT_TRUE(cuts.anatomy);
  EXPECT_NEAR(cuts.anatomy->menton.z(), 40, 1e-9);
  EXPECT_NEAR(cuts.bottom_z, 33, 1e-9);  // the body's lowest slice plus border_margin
  // Given, the cut is taken as it is.
  FaceCutOptions given;
  given.bottom_z = 20;
  EXPECT_NEAR(cuts_of(h.head, h.bone, given).bottom_z, 20, 1e-9);
}

TEST(FaceCuts, TheEarsFrontIsTheAuriclesFrontEdgeWhateverItsFlareBehind) {
  Head h;
  // The helix flaring out further behind the front (the widest rows of the head, 8 mm behind the ears' front): the
  // front stays at the auricle's front edge.
  fill(h.head, {2, 50, 96}, {118, 52, 124});
  const FaceAnatomy flared = *cuts_of(h.head, h.bone, FaceCutOptions()).anatomy;
  EXPECT_NEAR(flared.ear_front_y, 60, 1e-9);
  EXPECT_FALSE(flared.ears_estimated);
  // In front of the ears: a bump on the skin standing out 2 mm (a fold, less than kEarStandOut) over 20 mm of height,
  // and a thin flap standing out 8 mm over 6 mm of height (a strap's edge, shorter than kEarMinHeight): neither is ear.
  fill(h.head, {18, 64, 100}, {102, 66, 120});
  fill(h.head, {12, 70, 104}, {108, 72, 108});
  EXPECT_NEAR(cuts_of(h.head, h.bone, FaceCutOptions()).anatomy->ear_front_y, 60, 1e-9);
  // The +x ear 4 mm further back (a face is not quite symmetric): the cut goes in front of the more anterior.
  Head asymmetric;
  const GridGeometry& g = asymmetric.head.geometry;
  for (size_t v = 0; v < g.size(); ++v) {
    const auto [i, j, k] = g.ijk(v);
    const Eigen::Vector3d p = g.point(i, j, k);
    if (p.x() > 100 && p.y() >= 57 && p.y() <= 60) asymmetric.head.data[v] = 0;
  }
  fill(asymmetric.head, {100, 53, 100}, {110, 56, 120});
  const FaceAnatomy a = *cuts_of(asymmetric.head, asymmetric.bone, FaceCutOptions()).anatomy;
  EXPECT_NEAR(a.ear_fronts_y[0], 60, 1e-9);
  EXPECT_NEAR(a.ear_fronts_y[1], 56, 1e-9);
  EXPECT_NEAR(a.ear_front_y, 60, 1e-9);
  // A thin auricle further forward, 12 mm tall: the ears' front moves to it.
  fill(h.head, {12, 76, 100}, {108, 78, 110});
  EXPECT_NEAR(cuts_of(h.head, h.bone, FaceCutOptions()).posterior_y, 78 + 12, 1e-9);
}

TEST(FaceAnatomy, AHeadsTurnIsTheAngleOfItsSectionsMirrorSymmetry) {
  // The phantom turned about the vertical through its pivot: its face looks towards (-sin d, cos d, 0), a turn of -d;
  // with its shoulders, and with a block beside one cheek (a head rest's side) breaking the symmetry of some levels.
  for (const double degrees : {-30.0, -12.0, 0.0, 7.0, 18.0}) {
    Head h(rotation(degrees, Eigen::Vector3d::UnitZ()), true);
    EXPECT_NEAR(find_head_turn(h.head).degrees, -degrees, 1.0) << degrees;
    fill(h.head, {100, 30, 60}, {110, 50, 90});
    const HeadTurn turn = find_head_turn(h.head);
    EXPECT_NEAR(turn.degrees, -degrees, 1.5) << degrees << " with a block";
    EXPECT_LT((turn.axis - Eigen::Vector2d(60, 57)).norm(), 8.0) << degrees;  // near the sections' middle
  }
}

// A head whose width grows with its height more at its front than at its back (x within 10 + 40 (y - 20) / 70
// (z - 30) / 120 of 60, y in [20, 90], z in [30, 150]) with a nose (x in [56, 64], y up to 100, z in [80, 100]), posed
// about (60, 60, 90) as Head is: a tilted one's horizontal sections cut its two sides at heights whose widths differ
// more at the front than at the back.
Mask widening_head(const Eigen::Matrix3d& pose) {
  Mask m(grid(), 0);
  const Eigen::Vector3d pivot(60, 60, 90);
  const GridGeometry& g = m.geometry;
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const Eigen::Vector3d p = pivot + pose.transpose() * (g.point(i, j, k) - pivot);
        const double half_width = 10 + 40 * (p.y() - 20) / 70 * (p.z() - 30) / 120;
        const bool body =
            p.y() >= 20 && p.y() <= 90 && p.z() >= 30 && p.z() <= 150 && std::abs(p.x() - 60) <= half_width;
        const bool nose = std::abs(p.x() - 60) <= 4 && p.y() >= 90 && p.y() <= 100 && p.z() >= 80 && p.z() <= 100;
        m(i, j, k) = body || nose;
      }
  return m;
}

TEST(FaceAnatomy, ATiltedHeadsTurnIsThatOfItsMirrorPlaneIn3d) {
  // Tilted towards a shoulder (about its own front-to-back axis) and then turned about the vertical: the horizontal
  // sections' mirror lines turn with the tilt; the turn is the 3D mirror plane's.
  for (const double roll : {-15.0, 12.0, 20.0})
    for (const double degrees : {-12.0, 0.0, 8.0}) {
      const Mask head =
          widening_head(rotation(degrees, Eigen::Vector3d::UnitZ()) * rotation(roll, Eigen::Vector3d::UnitY()));
      EXPECT_NEAR(find_head_turn(head).degrees, -degrees, 1.0) << "roll " << roll << ", turn " << degrees;
    }
}

TEST(FaceCuts, ATurnedHeadsPosteriorCutIsInFrontOfTheMoreAnteriorEar) {
  for (const double degrees : {-15.0, -10.0, -2.0, 2.0, 10.0, 15.0}) {
    const Head h(rotation(degrees, Eigen::Vector3d::UnitZ()), false);
    // The ears' front edge (y = 60 at 50 mm either side of the pivot) turns forward on one side by 50 sin(angle) and
    // back on the other by as much; each ear's front is found, and the cut goes in front of both.
    const double anterior_ear = 60 + 50 * std::sin(std::abs(degrees) * M_PI / 180);
    const FaceCuts cuts = cuts_of(h.head, h.bone, FaceCutOptions());
    const FaceAnatomy& a = *cuts.anatomy;
    EXPECT_NEAR(std::max(a.ear_fronts_y[0], a.ear_fronts_y[1]), anterior_ear, 2.0) << degrees;  // a 2 mm grid
    EXPECT_NEAR(std::min(a.ear_fronts_y[0], a.ear_fronts_y[1]), 120 - anterior_ear, 2.0) << degrees;
    EXPECT_NEAR(a.ear_front_y, anterior_ear, 2.0) << degrees;
    EXPECT_GE(cuts.posterior_y, anterior_ear + 12 - 2.0) << degrees;
    EXPECT_NE(face_anatomy_text(a).find("front of the ears y " +
                                        [&] {
                                          std::ostringstream y;
                                          y.precision(1);
                                          y << std::fixed << a.ear_front_y << " (-x ear " << a.ear_fronts_y[0]
                                            << ", +x ear " << a.ear_fronts_y[1] << ")";
                                          return y.str();
                                        }()),
              std::string::npos)
        << face_anatomy_text(a);
  }
}

TEST(FaceCuts, ShouldersAndThingsAboveTheBrowAreNotEars) {
  Head h;
  // Wider than the ears: shoulders higher up, a brim above the glabella, a plate at the front quarter of the depth.
  fill(h.head, {0, 30, 12}, {120, 80, 20});
  fill(h.head, {0, 40, 150}, {120, 80, 154});
  fill(h.head, {0, 86, 110}, {120, 88, 112});
  const FaceCuts cuts = cuts_of(h.head, h.bone, FaceCutOptions());
  EXPECT_NEAR(cuts.centre_x, 60, 1e-9);  // all symmetric about x = 60
  EXPECT_NEAR(cuts.posterior_y, 72, 1e-9);
}

TEST(FaceCuts, GivenValuesAreTakenAsThey) {
  const Head h;
  FaceCutOptions o;
  o.top_z = 150.5;
  o.bottom_z = 12.25;
  o.posterior_y = 33;
  o.centre_x = 71;
  const Mask no_bone(h.head.geometry, 0);
  const FaceCuts cuts = cuts_of(h.head, no_bone, o);
  EXPECT_EQ(cuts.top_z, 150.5);
  EXPECT_EQ(cuts.bottom_z, 12.25);
  EXPECT_EQ(cuts.posterior_y, 33);
  EXPECT_EQ(cuts.centre_x, 71);
}

// The glabella read on the skin under an object over the brow (soft_tissue.cpp reads it there when the profile's lies
// on one) places the top cut instead of the profile's, and the anatomy says so.
TEST(FaceCuts, AGlabellaReadUnderAnObjectPlacesTheTopCut) {
  const Head h;
  FaceCutOptions o;
  o.glabella = Eigen::Vector3d(60, 91, 133);
  const FaceCuts cuts = cuts_of(h.head, h.bone, o);
  ASSERT_TRUE(cuts.anatomy);
  EXPECT_DOUBLE_EQ(cuts.top_z, 133 + o.brow_clearance);
  EXPECT_TRUE(cuts.anatomy->glabella_under_object);
  EXPECT_EQ(cuts.anatomy->glabella, *o.glabella);
  EXPECT_NE(face_anatomy_text(*cuts.anatomy).find("glabella (60.0, 91.0, 133.0) (on the skin under the object"),
            std::string::npos)
      << face_anatomy_text(*cuts.anatomy);
  // Without it, the profile's glabella (the brow's middle, z 140) places the cut.
  const FaceCuts profile = cuts_of(h.head, h.bone, FaceCutOptions{});
  EXPECT_NEAR(profile.top_z, 155, 1.0);
  EXPECT_FALSE(profile.anatomy->glabella_under_object);
}

TEST(FaceCuts, RejectsCutsThatLeaveNoFace) {
  const Head h;
  expect_error([&] { cuts_of(Mask(h.head.geometry, 0), h.bone, FaceCutOptions()); }, "the head mask is empty");
  FaceCutOptions o;
  o.top_z = 45;
  o.bottom_z = 40;
  expect_error([&] { cuts_of(h.head, h.bone, o); }, "must be well above the bottom cut");
  o.top_z = 30;  // upside down
  expect_error([&] { cuts_of(h.head, h.bone, o); }, "must be well above the bottom cut");
  // A head without a chin (no bone): the error names the option that places the bottom cut by hand.
  expect_error([&] { cuts_of(h.head, Mask(h.head.geometry, 0), FaceCutOptions()); }, "--bottom-cut");
}

// Cuts given as numbers: top z 160, bottom z 30, posterior y 70, mid-plane x 60, no jaw cut.
FaceCuts box_cuts() {
  FaceCuts cuts;
  cuts.top_z = 160;
  cuts.bottom_z = 30;
  cuts.posterior_y = 70;
  cuts.centre_x = 60;
  return cuts;
}

TEST(FaceCuts, PlanesPointOutOfTheModel) {
  FaceCuts cuts = box_cuts();
  std::vector<CutPlane> planes = cuts.planes();
  ASSERT_EQ(planes.size(), 3u);  // no jaw cut
  EXPECT_EQ(planes[0].side, V1);
  EXPECT_EQ(planes[1].side, V0);
  EXPECT_EQ(planes[2].side, U0);
  const Eigen::Vector3d inside(60, 90, 100);
  for (const CutPlane& p : planes) EXPECT_LT(p.distance(inside), 0);
  EXPECT_NEAR(planes[0].distance({0, 0, 165}), 5, 1e-12);   // above the top
  EXPECT_NEAR(planes[1].distance({0, 0, 20}), 10, 1e-12);   // below the bottom
  EXPECT_NEAR(planes[2].distance({0, 63, 0}), 7, 1e-12);    // behind the posterior cut
  EXPECT_NEAR(planes[2].distance({200, 70, 0}), 0, 1e-12);  // on it

  // The jaw cut rises at 45 degrees from the bottom cut to z = jaw_z on the posterior cut.
  cuts.jaw_z = 60;
  planes = cuts.planes();
  ASSERT_EQ(planes.size(), 4u);
  const CutPlane& jaw = planes[3];
  EXPECT_EQ(jaw.side, V0);
  EXPECT_NEAR(jaw.normal.norm(), 1, 1e-15);
  EXPECT_NEAR(jaw.distance({60, 70, 60}), 0, 1e-12);                    // meets the posterior cut at z = jaw_z
  EXPECT_NEAR(jaw.distance({60, 100, 30}), 0, 1e-12);                   // meets the bottom cut 30 mm further forward
  EXPECT_NEAR(jaw.distance({60, 72, 40}), 18 / std::sqrt(2.0), 1e-12);  // under the jaw: cut away
  EXPECT_LT(jaw.distance({60, 110, 35}), 0);                            // the chin stays
  EXPECT_LT(jaw.distance(inside), 0);
}

TEST(FaceCuts, AnObliquePosteriorCutAndItsJawCutTurnTogether) {
  // y = 70 + 0.1 (x - 60) at the posterior cut; the jaw cut rises from it as from a coronal one, measured along y.
  FaceCuts cuts = box_cuts();
  cuts.posterior_slope = 0.1;
  cuts.jaw_z = 60;
  EXPECT_NEAR(cuts.posterior_y_at(0), 64, 1e-12);
  EXPECT_NEAR(cuts.posterior_turn_degrees(), std::atan(0.1) * 180 / M_PI, 1e-12);
  const std::vector<CutPlane> planes = cuts.planes();
  ASSERT_EQ(planes.size(), 4u);
  const CutPlane &posterior = planes[2], &jaw = planes[3];
  EXPECT_NEAR(posterior.normal.norm(), 1, 1e-15);
  EXPECT_NEAR(jaw.normal.norm(), 1, 1e-15);
  for (const double x : {0.0, 60.0, 130.0}) {
    const double y = cuts.posterior_y_at(x);
    EXPECT_NEAR(posterior.distance({x, y, 90}), 0, 1e-12) << x;
    EXPECT_GT(posterior.distance({x, y - 1, 90}), 0) << x;  // behind it: cut away
    EXPECT_LT(posterior.distance({x, y + 1, 90}), 0) << x;
    EXPECT_NEAR(jaw.distance({x, y, 60}), 0, 1e-12) << x;       // meets the posterior cut at z = jaw_z
    EXPECT_NEAR(jaw.distance({x, y + 30, 30}), 0, 1e-12) << x;  // and the bottom cut 30 mm further forward
    EXPECT_GT(jaw.distance({x, y + 2, 40}), 0) << x;            // under the jaw: cut away
  }
}

// find_jaw_cut looks at the posterior plane's voxel row (y = 70: j = 35), within one voxel (2 mm) of x = 60, in the
// lower half of the face (z <= (30 + 160) / 2 = 95).
TEST(FaceCuts, TheJawCutIsAboveTheHighestModelVoxelOnThePosteriorCutsMidLine) {
  FaceCuts cuts = box_cuts();
  Mask model(grid(), 0);
  FaceCuts none = cuts;
  find_jaw_cut(model, 3, none);
  EXPECT_EQ(none.jaw_z, -std::numeric_limits<double>::infinity());  // nothing there: no jaw cut

  fill(model, {60, 70, 30}, {60, 70, 70});    // the submental tissue on the mid-line, up to z = 70
  fill(model, {60, 70, 100}, {60, 70, 130});  // above the lower half: the scalp, not the jaw
  fill(model, {66, 70, 30}, {66, 70, 90});    // 6 mm off the mid-line
  fill(model, {60, 74, 30}, {60, 74, 90});    // two rows in front of the posterior cut
  FaceCuts c = cuts;
  find_jaw_cut(model, 3, c);
  EXPECT_NEAR(c.jaw_z, 73, 1e-9);
  EXPECT_EQ(c.top_z, cuts.top_z);  // nothing else changes
  EXPECT_EQ(c.posterior_y, cuts.posterior_y);

  fill(model, {62, 70, 80}, {62, 70, 80});  // one voxel off the mid-line still counts
  c = cuts;
  find_jaw_cut(model, 3, c);
  EXPECT_NEAR(c.jaw_z, 83, 1e-9);

  c = cuts;
  c.posterior_y = 69.2;  // the nearest voxel row is still y = 70
  find_jaw_cut(model, 0.5, c);
  EXPECT_NEAR(c.jaw_z, 80.5, 1e-9);

  c = cuts;
  c.posterior_y = 500;  // beyond the grid: no jaw cut
  find_jaw_cut(model, 3, c);
  EXPECT_EQ(c.jaw_z, -std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace facehex
