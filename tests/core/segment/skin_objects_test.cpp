#include "core/segment/skin_objects.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "core/face/face_landmarks.h"
#include "core/face/landmark_file.h"
#include "core/fields/constraint_set.h"
#include "core/segment/ct_volume.h"
#include "core/segment/soft_tissue.h"
#include "core/segment/thresholds.h"
#include "tests/core/segment/phantom.h"

namespace facehex {
namespace {

// A face's front above the nose tip in its head frame (plane x = 0, +y anterior): the nasal dorsum receding up to a
// nasion hollow at z = -20, the brow coming forward above it, the forehead receding; with a strap on it from z_low to
// z_high, `thickness` in front of the skin.
struct ForeheadPhantom {
  static constexpr double kTipZ = -48;  // the nose tip's height, below the grid's bottom edge at z = -50 plus 2
  double z_low = 0, z_high = 0, thickness = 0;
  static double skin(double x, double z) {
    const double dorsum = z < -20 ? 0.6 * (-20 - z) : 0;  // the nose comes forward below the nasion
    return 10 - 0.01 * x * x + dorsum + 3 * std::exp(-(z + 8) * (z + 8) / 60) - 0.002 * (z + 20) * (z + 20);
  }
  double front(double x, double z) const { return skin(x, z) + (z >= z_low && z <= z_high ? thickness : 0); }
};

std::vector<SkinObject> objects_on(const ForeheadPhantom& face, const MidSagittalPlane& plane) {
  const HeadTurn frame = head_turn_of(plane);
  const Field ct = testing::face_front_phantom([&face](double x, double z) { return face.front(x, z); }, frame);
  const Eigen::Vector3d tip(0, ForeheadPhantom::skin(0, ForeheadPhantom::kTipZ), ForeheadPhantom::kTipZ);
  return find_skin_objects(ct, 0, plane, frame.to_model(tip));
}

TEST(SkinObjects, AStrapOnTheForeheadItsEdgesThicknessAndTheSkinUnderItUprightAndTurned) {
  for (const double turn_degrees : {0.0, 10.0, -15.0})
    for (const auto& [z_low, z_high, thickness] :
         {std::tuple{-10.0, 10.0, 4.0}, std::tuple{-25.0, -5.0, 2.5}, std::tuple{0.0, 25.0, 6.0}}) {
      MidSagittalPlane plane;
      plane.turn = std::tan(turn_degrees * M_PI / 180);
      plane.y = 10;
      const std::string what = "turned " + std::to_string(turn_degrees) + ", strap " + std::to_string(z_low) + " to " +
                               std::to_string(z_high) + ", " + std::to_string(thickness) + " mm";
      const std::vector<SkinObject> found = objects_on({z_low, z_high, thickness}, plane);
      ASSERT_EQ(found.size(), 1u) << what;
      const SkinObject& o = found[0];
      // The edges where the grey values cross between two slices 0.5 mm apart, found every 0.25 mm.
      EXPECT_NEAR(o.z_low, z_low, 0.5) << what;
      EXPECT_NEAR(o.z_high, z_high, 0.5) << what;
      EXPECT_NEAR(o.thickness_low, thickness, 0.3) << what;
      EXPECT_NEAR(o.thickness_high, thickness, 0.3) << what;
      ASSERT_GE(o.skin.size(), 2u);
      EXPECT_LE(o.skin.front().x(), z_low - 4) << what;
      EXPECT_GE(o.skin.back().x(), z_high + 4) << what;
      double worst = 0;
      for (const Eigen::Vector2d& p : o.skin)
        worst = std::max(worst, std::abs(p.y() - ForeheadPhantom::skin(0, p.x())));
      EXPECT_LT(worst, 0.5) << what << ": the skin under the strap is read up to " << worst << " mm off";
    }
}

TEST(SkinObjects, NoneOnABareFaceOnTapeThinnerThanTheStepOrOnAnObjectWhoseUpperEdgeTheScanDoesNotShow) {
  EXPECT_TRUE(objects_on({}, MidSagittalPlane{}).empty());  // the nasion's and the brow's bends are no edges
  EXPECT_TRUE(objects_on({-10, 10, 1.0}, MidSagittalPlane{}).empty());
  EXPECT_TRUE(objects_on({10, 40, 4.0}, MidSagittalPlane{}).empty());  // the grid ends at z = 30
}

// The Visible Human's CT (../shared, optional) with a strap of a soft tissue's density across its forehead: a layer
// `thickness` mm thick in front of each column's most anterior skin voxel, from z_low to z_high (as scripts/strap_ct.py
// makes it).
CtVolume visible_human_with_strap(double z_low, double z_high, double thickness) {
  CtVolume ct = read_ct_volume(std::string(FACEHEX_SHARED_DIR) + "/data/ct/vhfemale-head.mha");
  const TissueThresholds t = estimate_thresholds(ct.intensity);
  Field& f = ct.intensity;
  const GridGeometry& g = f.geometry;
  const int layer = static_cast<int>(std::lround(thickness / g.spacing.y()));
  for (int k = 0; k < g.dims[2]; ++k) {
    if (g.point(0, 0, k).z() < z_low || g.point(0, 0, k).z() > z_high) continue;
    for (int i = 0; i < g.dims[0]; ++i)
      for (int j = g.dims[1] - 1; j >= 0; --j)
        if (f(i, j, k) > t.skin) {
          for (int s = 1; s <= layer && j + s < g.dims[1]; ++s) f(i, j + s, k) = 0.5 * (t.skin + t.bone);
          break;
        }
  }
  return ct;
}

std::map<std::string, Eigen::Vector3d> hand_placed_visible_human() {
  std::map<std::string, Eigen::Vector3d> placed;
  for (const NamedLandmark& l :
       read_landmark_file(std::string(FACEHEX_TEST_DATA_DIR) + "/landmarks/vhfemale-head.json"))
    placed[l.name] = l.position;
  return placed;
}

TEST(SkinObjects, VisibleHumanBareAndWithAStrapReadFromItsCt) {
  if (!std::filesystem::exists(std::string(FACEHEX_SHARED_DIR) + "/data/ct/vhfemale-head.mha"))
    GTEST_SKIP() << "no shared data";
  const std::map<std::string, Eigen::Vector3d> placed = hand_placed_visible_human();
  const MidSagittalPlane plane = testing::visible_human_plane();
  const auto objects = [&](const CtVolume& ct) {
    return find_skin_objects(ct.intensity, estimate_thresholds(ct.intensity).skin, plane, placed.at("pronasale"));
  };
  EXPECT_TRUE(objects(read_ct_volume(std::string(FACEHEX_SHARED_DIR) + "/data/ct/vhfemale-head.mha")).empty());
  for (const auto& [z_low, z_high, thickness] : {std::tuple{150.0, 170.0, 4.0}, std::tuple{125.0, 145.0, 3.0}}) {
    const std::vector<SkinObject> found = objects(visible_human_with_strap(z_low, z_high, thickness));
    ASSERT_EQ(found.size(), 1u) << "strap " << z_low << " to " << z_high;
    // The slices are 1 mm apart: the edges lie between the strap's first or last slice and the next.
    EXPECT_NEAR(found[0].z_low, z_low - 0.5, 1.0);
    EXPECT_NEAR(found[0].z_high, z_high + 0.5, 1.0);
    EXPECT_NEAR(found[0].thickness_low, thickness, 0.75);
    EXPECT_NEAR(found[0].thickness_high, thickness, 0.75);
  }
}

TEST(SkinObjects, VisibleHumanWithAForeheadStrapKeepsItsGlabellaOnTheSkinUnlessObjectsAreOff) {
  // Segmented whole: the model carries the strap as soft tissue, its landmarks are read on the skin under it.
  if (!std::filesystem::exists(std::string(FACEHEX_SHARED_DIR) + "/data/ct/vhfemale-head.mha"))
    GTEST_SKIP() << "no shared data";
  const PatientModel model = build_patient_model(visible_human_with_strap(150, 170, 4), SegmentOptions{});
  const FaceLandmarks l =
      find_face_landmarks(model.mesh.V, side_mask_of(model.mesh), landmark_options_for(model.mesh, "model"));
  ASSERT_EQ(l.skin_objects.size(), 1u);
  EXPECT_NE(landmarks_text(l, "").find("an object lies on the skin's front from z = "), std::string::npos);
  // On the strap's front the glabella lay 8 mm from the hand-placed one, 4 mm in front of the skin; the finder's own
  // on the bare CT lies 1.9 mm from it, on a flat brow whose middle moves by a millimetre or two with the skin read.
  const Eigen::Vector3d glabella = l.points.at("glabella"), placed = hand_placed_visible_human().at("glabella");
  EXPECT_LT((glabella - placed).norm(), 3.0) << "glabella at " << glabella.transpose();
  EXPECT_NEAR(glabella.y(), placed.y(), 1.0) << "glabella at " << glabella.transpose();
  // The top cut lies brow_clearance above the skin's glabella, not above the strap's lower edge, which the CT's
  // profile takes for the brow.
  ASSERT_TRUE(model.cuts.anatomy);
  EXPECT_TRUE(model.cuts.anatomy->glabella_under_object);
  EXPECT_NEAR(model.cuts.top_z, placed.z() + model.options.cuts.brow_clearance, 2.5);

  // Without looking for objects (--skin-objects off) the glabella is read on the strap's front.
  SegmentOptions off;
  off.find_skin_objects = false;
  const PatientModel as_segmented = build_patient_model(visible_human_with_strap(150, 170, 4), off);
  const FaceLandmarks on_front = find_face_landmarks(as_segmented.mesh.V, side_mask_of(as_segmented.mesh),
                                                     landmark_options_for(as_segmented.mesh, "model"));
  EXPECT_TRUE(on_front.skin_objects.empty());
  EXPECT_GT(on_front.points.at("glabella").y(), placed.y() + 2) << on_front.points.at("glabella").transpose();
  EXPECT_FALSE(as_segmented.cuts.anatomy->glabella_under_object);
}

}  // namespace
}  // namespace facehex
