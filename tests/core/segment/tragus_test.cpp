#include "core/segment/tragus.h"

#include <gtest/gtest.h>

#include <cmath>

namespace facehex {
namespace {

// A head on a 1 mm grid: an elliptic cylinder of half-widths 70 (x) and 90 (y) about x = 100, y = 100, with an
// auricle on the +x side, a block standing out from the head's side (x 165 to 185, y 60 to 110, z 50 to 85: longer than
// the 35 mm searched behind its front, as an auricle is) whose hollow (x from 172 out, y 85 to 100, z 58 to 75) opens
// sideways: its front wall is the row y = 100, and the tragus's free edge in front of it reaches out to x 185. `hollow`
// false: the block is solid.
struct EarPhantom {
  Mask head;
  FaceAnatomy anatomy;
};
EarPhantom ear_phantom(bool hollow) {
  EarPhantom p;
  GridGeometry g;
  g.dims = {200, 200, 120};
  p.head = Mask(g, 0);
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const double x = i, y = j, z = k;
        const bool in_head = std::pow((x - 100) / 70, 2) + std::pow((y - 100) / 90, 2) <= 1;
        const bool in_block = x >= 165 && x <= 185 && y >= 60 && y <= 110 && z >= 50 && z <= 85;
        const bool in_hollow = hollow && x >= 172 && y >= 85 && y <= 104 && z >= 58 && z <= 75;
        p.head(i, j, k) = (in_head || in_block) && !in_hollow;
      }
  p.anatomy.centre_x = 100;
  p.anatomy.pronasale = Eigen::Vector3d(100, 190, 95);
  p.anatomy.glabella = Eigen::Vector3d(100, 185, 110);
  p.anatomy.ear_fronts_y = {-std::numeric_limits<double>::infinity(), 110};
  p.anatomy.ear_front_y = 110;
  return p;
}

TEST(Tragus, TheFreeEdgeInFrontOfTheEarsHollow) {
  const EarPhantom p = ear_phantom(true);
  const Tragi tragi = find_tragi(p.head, p.anatomy);
  EXPECT_FALSE(tragi[0]);  // no auricle on the -x side
  ASSERT_TRUE(tragi[1]);
  // Between the hollow's front row (y 104) and the next, at the middle of the wall's levels, as far out as the tragus.
  EXPECT_NEAR(tragi[1]->point.x(), 185, 1e-9);
  EXPECT_NEAR(tragi[1]->point.y(), 104.5, 1e-9);
  EXPECT_NEAR(tragi[1]->point.z(), 66.5, 1e-9);
  EXPECT_FALSE(tragi[1]->estimated);
}

TEST(Tragus, TheMirroredEarGivesTheMirroredTragus) {
  EarPhantom p = ear_phantom(true);
  Mask mirrored = p.head;
  const auto& d = p.head.geometry.dims;
  for (int k = 0; k < d[2]; ++k)
    for (int j = 0; j < d[1]; ++j)
      for (int i = 0; i < d[0]; ++i) mirrored(i, j, k) = p.head(d[0] - 1 - i, j, k);
  p.anatomy.centre_x = 0.5 * (d[0] - 1) - (100 - 0.5 * (d[0] - 1));
  p.anatomy.ear_fronts_y = {110, -std::numeric_limits<double>::infinity()};
  const Tragi tragi = find_tragi(mirrored, p.anatomy);
  EXPECT_FALSE(tragi[1]);
  ASSERT_TRUE(tragi[0]);
  EXPECT_NEAR(tragi[0]->point.x(), d[0] - 1 - 185, 1e-9);
  EXPECT_NEAR(tragi[0]->point.y(), 104.5, 1e-9);
  EXPECT_NEAR(tragi[0]->point.z(), 66.5, 1e-9);
}

TEST(Tragus, AWallFarBehindTheAuriclesFrontEdgeIsNoTragus) {
  // The auricle's front edge 14.5 mm in front of the wall: the wall is one inside the concha.
  EarPhantom p = ear_phantom(true);
  p.anatomy.ear_fronts_y[1] = 119;
  EXPECT_FALSE(find_tragi(p.head, p.anatomy)[1]);
  p.anatomy.ear_fronts_y[1] = 112;  // 7.5 mm: still the tragus
  EXPECT_TRUE(find_tragi(p.head, p.anatomy)[1]);
}

TEST(Tragus, NoHollowNoTragus) {
  const EarPhantom p = ear_phantom(false);
  EXPECT_FALSE(find_tragi(p.head, p.anatomy)[1]);
}

TEST(Tragus, EstimatedWhereNoAuricleStoodOut) {
  EarPhantom p = ear_phantom(true);
  p.anatomy.ears_estimated = true;
  const Tragi tragi = find_tragi(p.head, p.anatomy);
  ASSERT_TRUE(tragi[1]);
  EXPECT_TRUE(tragi[1]->estimated);
}

TEST(Tragus, AShallowDentIsNoEar) {
  // A hollow 4 mm deep (less than kMinDepth) over the same area: a skin fold, not the concha.
  EarPhantom p = ear_phantom(false);
  for (int k = 58; k <= 75; ++k)
    for (int j = 85; j <= 104; ++j)
      for (int i = 182; i <= 185; ++i) p.head(i, j, k) = 0;
  EXPECT_FALSE(find_tragi(p.head, p.anatomy)[1]);
}

}  // namespace
}  // namespace facehex
