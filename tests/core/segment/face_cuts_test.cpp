#include "core/segment/face_cuts.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

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

// The synthetic head: a block x in [20, 100] (mid-plane x = 60), y in [20, 100] (back to front), z in [10, 170], with
// ears x in [10, 110] at y in [50, 60], z in [100, 120]; the chin bone x in [54, 66], y in [84, 94], z in [40, 50].
// Known cuts with the default options: centre_x 60, bottom 40 - 10 = 30, top 30 + 130 = 160, posterior 60 + 10 = 70.
struct Head {
  Mask head, bone;
  Head() : head(grid(), 0), bone(grid(), 0) {
    fill(head, {20, 20, 10}, {100, 100, 170});
    fill(head, {10, 50, 100}, {110, 60, 120});
    fill(bone, {54, 84, 40}, {66, 94, 50});
  }
};

void expect_error(const std::function<void()>& run, const std::string& words) {
  try {
    run();
    ADD_FAILURE() << "expected facehex::Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.subject(), "segment") << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << "'" << e.what() << "' lacks '" << words << "'";
  }
}

TEST(FaceCuts, AutomaticCutsOfASyntheticHead) {
  const Head h;
  const FaceCuts cuts = find_face_cuts(h.head, h.bone, FaceCutOptions());
  EXPECT_NEAR(cuts.centre_x, 60, 1e-9);
  EXPECT_NEAR(cuts.bottom_z, 30, 1e-9);
  EXPECT_NEAR(cuts.top_z, 160, 1e-9);
  EXPECT_NEAR(cuts.posterior_y, 70, 1e-9);
  EXPECT_EQ(cuts.jaw_z, -std::numeric_limits<double>::infinity());  // find_jaw_cut's business
}

TEST(FaceCuts, TheClearancesAndTheFaceHeightAreOptions) {
  const Head h;
  FaceCutOptions o;
  o.chin_clearance = 4;
  o.ear_clearance = 6;
  o.face_height = 100;
  const FaceCuts cuts = find_face_cuts(h.head, h.bone, o);
  EXPECT_NEAR(cuts.bottom_z, 36, 1e-9);
  EXPECT_NEAR(cuts.top_z, 136, 1e-9);
  EXPECT_NEAR(cuts.posterior_y, 66, 1e-9);
}

TEST(FaceCuts, TheChinIsTheLowestAnteriorBoneNearTheMidPlane) {
  Head h;
  // Bone lower down that is not the chin: the spine (posterior), a lateral bone 16 mm off the mid-plane, and bone
  // within the anterior quarter (y >= 100 - 0.25 * 80 = 80) but just behind it (y = 78).
  fill(h.bone, {56, 30, 14}, {64, 40, 36});
  fill(h.bone, {76, 90, 20}, {78, 94, 24});
  fill(h.bone, {58, 78, 16}, {62, 78, 20});
  EXPECT_NEAR(find_face_cuts(h.head, h.bone, FaceCutOptions()).bottom_z, 30, 1e-9);
  // Bone 14 mm off the mid-plane, at the front limit of the anterior quarter: it is the chin now.
  fill(h.bone, {74, 80, 34}, {74, 80, 34});
  EXPECT_NEAR(find_face_cuts(h.head, h.bone, FaceCutOptions()).bottom_z, 24, 1e-9);
}

TEST(FaceCuts, CutsStayInsideTheCt) {
  Head h;
  // A chin at the head's lowest slice (z = 10): 10 - 10 = 0 is the CT's bottom; the cut stays border_margin inside.
  fill(h.bone, {58, 90, 10}, {62, 92, 12});
  FaceCutOptions o;
  EXPECT_NEAR(find_face_cuts(h.head, h.bone, o).bottom_z, 3, 1e-9);
  o.border_margin = 5;
  EXPECT_NEAR(find_face_cuts(h.head, h.bone, o).bottom_z, 5, 1e-9);
  // No bone at all: the bottom of the CT (plus the margin).
  const Mask no_bone(h.head.geometry, 0);
  EXPECT_NEAR(find_face_cuts(h.head, no_bone, FaceCutOptions()).bottom_z, 3, 1e-9);
  // A face taller than the CT: the top cut is border_margin below its top (180 - 3).
  const Head fresh;
  o = FaceCutOptions();
  o.face_height = 200;
  EXPECT_NEAR(find_face_cuts(fresh.head, fresh.bone, o).top_z, 177, 1e-9);
}

TEST(FaceCuts, TheEarsFrontIsTheMostAnteriorRowNearlyAsWideAsTheWidest) {
  Head h;
  // A lobe in front of the ears 96 mm wide (within 5 mm of the ears' 100) and, further forward, one 92 mm wide.
  fill(h.head, {12, 62, 100}, {108, 64, 110});
  fill(h.head, {14, 66, 100}, {106, 70, 110});
  EXPECT_NEAR(find_face_cuts(h.head, h.bone, FaceCutOptions()).posterior_y, 64 + 10, 1e-9);
}

TEST(FaceCuts, OnlyTheUpperFaceAndTheMiddleOfTheHeadsDepthCanBeEars) {
  Head h;
  // Shoulders, wider than the ears, but below the upper 60 % of the face (z < 30 + 0.4 * 130 = 82).
  fill(h.head, {0, 30, 12}, {120, 90, 20});
  // A wide brim above the top cut (z > 160), and a wide plate at the front quarter of the head's depth (y > 80).
  fill(h.head, {0, 40, 164}, {120, 80, 168});
  fill(h.head, {0, 86, 130}, {120, 90, 140});
  const FaceCuts cuts = find_face_cuts(h.head, h.bone, FaceCutOptions());
  EXPECT_NEAR(cuts.centre_x, 60, 1e-9);  // all symmetric about x = 60
  EXPECT_NEAR(cuts.posterior_y, 70, 1e-9);
}

TEST(FaceCuts, TheCentreIsTheMeanXOfTheHead) {
  Head h;
  // 41 x 41 x 81 voxels centred on x = 60, plus a block of 11 x 11 x 11 voxels centred on x = 110.
  h.head = Mask(grid(), 0);
  fill(h.head, {20, 20, 10}, {100, 100, 170});
  fill(h.head, {100.5, 40, 100}, {120, 60, 120});
  const double big = 41.0 * 41 * 81, small = 10.0 * 11 * 11;  // x = 102 ... 120: 10 voxels
  const FaceCutOptions given = [] {
    FaceCutOptions o;
    o.posterior_y = 50;
    return o;
  }();
  EXPECT_NEAR(find_face_cuts(h.head, h.bone, given).centre_x, (60 * big + 111 * small) / (big + small), 1e-9);
}

TEST(FaceCuts, GivenValuesAreTakenAsThey) {
  const Head h;
  FaceCutOptions o;
  o.top_z = 150.5;
  o.bottom_z = 12.25;
  o.posterior_y = 33;
  o.centre_x = 71;
  const Mask no_bone(h.head.geometry, 0);
  const FaceCuts cuts = find_face_cuts(h.head, no_bone, o);
  EXPECT_EQ(cuts.top_z, 150.5);
  EXPECT_EQ(cuts.bottom_z, 12.25);
  EXPECT_EQ(cuts.posterior_y, 33);
  EXPECT_EQ(cuts.centre_x, 71);
}

TEST(FaceCuts, RejectsCutsThatLeaveNoFace) {
  const Head h;
  expect_error([&] { find_face_cuts(Mask(h.head.geometry, 0), h.bone, FaceCutOptions()); }, "the head mask is empty");
  FaceCutOptions o;
  o.top_z = 45;
  o.bottom_z = 40;
  expect_error([&] { find_face_cuts(h.head, h.bone, o); }, "must be well above the bottom cut");
  o.top_z = 30;  // upside down
  expect_error([&] { find_face_cuts(h.head, h.bone, o); }, "must be well above the bottom cut");
  // A CT 14 mm tall: 3 mm margins leave 8 mm between the cuts.
  Mask slab(grid(14), 0), slab_bone(grid(14), 0);
  fill(slab, {20, 20, 0}, {100, 100, 14});
  expect_error([&] { find_face_cuts(slab, slab_bone, FaceCutOptions()); }, "must be well above the bottom cut");
  // Head only below the upper face: nowhere to look for the ears.
  Mask low(grid(), 0);
  fill(low, {20, 20, 0}, {100, 100, 60});
  o = FaceCutOptions();
  o.bottom_z = 30;
  o.top_z = 160;
  expect_error([&] { find_face_cuts(low, h.bone, o); }, "no head between the bottom and top cuts");
}

TEST(FaceCuts, PlanesPointOutOfTheModel) {
  FaceCuts cuts;
  cuts.top_z = 160;
  cuts.bottom_z = 30;
  cuts.posterior_y = 70;
  cuts.centre_x = 60;
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

// find_jaw_cut looks at the posterior plane's voxel row (y = 70: j = 35), within one voxel (2 mm) of x = 60, in the
// lower half of the face (z <= (30 + 160) / 2 = 95).
TEST(FaceCuts, TheJawCutIsAboveTheHighestModelVoxelOnThePosteriorCutsMidLine) {
  FaceCuts cuts;
  cuts.top_z = 160;
  cuts.bottom_z = 30;
  cuts.posterior_y = 70;
  cuts.centre_x = 60;
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
