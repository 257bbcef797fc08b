#include "core/segment/palate_pitch.h"

#include <gtest/gtest.h>

#include <cmath>

namespace facehex {
namespace {

// A head (a filled ellipsoid, 1 mm voxels) whose only bone is a plate 2 mm thick, `length` mm long and 30 mm wide
// about the mid-plane x = 40, sloping `degrees` up to the front, its middle at y 112, z 70 (the front of the head
// at y 150): a hard palate with a known slope.
struct PalatePhantom {
  Mask head, bone;
  PalatePhantom(double degrees, double length) {
    GridGeometry g;
    g.dims = {80, 160, 160};
    g.spacing = Eigen::Vector3d::Ones();
    g.origin = Eigen::Vector3d::Zero();
    head = Mask(g, 0);
    bone = Mask(g, 0);
    const double t = degrees * M_PI / 180;
    const Eigen::Vector2d along(std::cos(t), std::sin(t)), across(-std::sin(t), std::cos(t)), middle(112, 70);
    for (int k = 0; k < g.dims[2]; ++k)
      for (int j = 0; j < g.dims[1]; ++j)
        for (int i = 0; i < g.dims[0]; ++i) {
          const Eigen::Vector3d p = g.point(i, j, k);
          const Eigen::Vector3d q = (p - Eigen::Vector3d(40, 80, 80)).cwiseQuotient(Eigen::Vector3d(35, 70, 70));
          if (q.squaredNorm() > 1) continue;
          head(i, j, k) = 1;
          const Eigen::Vector2d yz = Eigen::Vector2d(p.y(), p.z()) - middle;
          bone(i, j, k) =
              std::abs(p.x() - 40) <= 15 && std::abs(yz.dot(across)) <= 1.0 && std::abs(yz.dot(along)) <= 0.5 * length;
        }
  }
};

TEST(PalatePitch, APlateWithAKnownSlopeGivesItsSlope) {
  for (const double degrees : {-22.0, 0.0, 9.0, 17.0, 31.0}) {
    const PalatePhantom phantom(degrees, 40);
    const std::optional<double> pitch = palate_pitch(phantom.head, phantom.bone, 40);
    ASSERT_TRUE(pitch) << degrees;
    EXPECT_NEAR(*pitch, degrees, 1.0);
  }
}

TEST(PalatePitch, NoPalateWhereThereIsNoPlateOrOnlyAShortOne) {
  const PalatePhantom none(0, 0);
  EXPECT_FALSE(palate_pitch(none.head, none.bone, 40));
  const PalatePhantom short_one(5, kMinPalateLength - 5);
  EXPECT_FALSE(palate_pitch(short_one.head, short_one.bone, 40));
  // A band beside the plate sees no bone.
  const PalatePhantom beside(5, 40);
  EXPECT_FALSE(palate_pitch(beside.head, beside.bone, 70));
}

TEST(PalatePitch, ThickBoneAboveOrBelowIsNoPalate) {
  // The plate with bone filling the 15 mm below it (a jaw, not a palate over the tongue).
  PalatePhantom jaw(0, 40);
  const GridGeometry& g = jaw.bone.geometry;
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const Eigen::Vector3d p = g.point(i, j, k);
        if (jaw.head(i, j, k) && std::abs(p.x() - 40) <= 15 && p.z() >= 55 && p.z() < 69 && std::abs(p.y() - 112) <= 20)
          jaw.bone(i, j, k) = 1;
      }
  EXPECT_FALSE(palate_pitch(jaw.head, jaw.bone, 40));
}

}  // namespace
}  // namespace facehex
