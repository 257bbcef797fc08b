#include "core/face/face_landmarks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/fields/constraint_set.h"
#include "core/mesh/sides.h"
#include "core/util/error.h"

namespace facehex {
namespace {

double bump(double t, double centre, double sigma) {
  return std::exp(-(t - centre) * (t - centre) / (2 * sigma * sigma));
}

// A phantom skin: the surface y(x, z) sampled every 0.5 mm, all on the skin side (w1), looking to +y with +z up. Its
// mid-sagittal profile has a nose (20 mm, at z = 0), a dip below it (z = -14), upper and lower lips (z = -24, -38)
// with the lip contact between (z = -31), the nose root (z = 26) and the brow ridge (z = 40); the extremes of the
// summed profile lie within 0.6 mm of these centres (computed once, numerically). The nose is narrow (8 mm), the
// rest wide (25 mm), and the face is curved sideways. The lips end at the mouth corners: their relief tapers off
// (a cosine) from 20 to 26 mm either side of the midline. The x range is not symmetric about the midline x0, so the
// midline must be found from the nose, not the middle of the range.
struct PhantomFace {
  static constexpr double x0 = 7.0;
  Eigen::MatrixXd V;
  Eigen::VectorXi side_mask;

  // lips: the relief of the dip and the lips, 1 as described; a flat profile's lips stand out by less. dz: the
  // sampling in z (mm; x is sampled every 0.5 mm). clip: where given, the face above the nose tip stands as far
  // forward as the tip (a forehead beyond the scan's field of view, like the nose) and the scan cuts the front flat
  // at y = clip.
  explicit PhantomFace(double lips = 1.0, double dz = 0.5, std::optional<double> clip = std::nullopt) {
    const int nx = 261, nz = static_cast<int>(130 / dz) + 1;  // x0 - 60 .. x0 + 70, z -70 .. 60
    V.resize(nx * nz, 3);
    for (int i = 0; i < nx; ++i)
      for (int k = 0; k < nz; ++k) {
        const double x = x0 - 60 + 0.5 * i, z = -70 + dz * k, dx = x - x0;
        const double wide = -3 * lips * bump(z, -14, 3) - 4 * bump(z, 26, 4) + 6 * bump(z, 40, 5);
        const double mouth = lips * (6 * bump(z, -24, 4) - 4 * bump(z, -31, 2) + 6 * bump(z, -38, 4));
        const double taper = std::abs(dx) <= 20   ? 1.0
                             : std::abs(dx) >= 26 ? 0.0
                                                  : 0.5 * (1 + std::cos(M_PI * (std::abs(dx) - 20) / 6));
        double y = 80 - 0.01 * dx * dx + 20 * bump(z, 0, 6) * bump(dx, 0, 8) + (wide + mouth * taper) * bump(dx, 0, 25);
        if (clip) y = std::min(*clip, y + (z > 0 ? 20 * (1 - bump(z, 0, 6)) * bump(dx, 0, 25) : 0.0));
        V.row(i * nz + k) << x, y, z;
      }
    side_mask = Eigen::VectorXi::Constant(V.rows(), side_bit(W1));
  }
};

TEST(FaceLandmarks, PhantomLandmarksWithinOneAndAHalfMillimetres) {
  const PhantomFace face;
  const FaceLandmarks l = find_face_landmarks(face.V, face.side_mask);
  constexpr double tolerance = 1.5;  // mm: 1 mm profile bins on a 0.5 mm sampling
  EXPECT_NEAR(l.x_mid, PhantomFace::x0, 0.5);
  const std::map<std::string, double> expected_z = {
      {"pronasale", 0},          {"subnasale", -14.6}, {"labrale superius", -24}, {"stomion", -31},
      {"labrale inferius", -38}, {"nasion", 25.8},     {"glabella", 40}};
  for (const auto& [name, z] : expected_z) {
    ASSERT_TRUE(l.points.count(name)) << name;
    const Eigen::Vector3d p = l.points.at(name);
    EXPECT_NEAR(p.z(), z, tolerance) << name;
    EXPECT_NEAR(p.x(), PhantomFace::x0, 3.0) << name;  // within the profile band
  }
  EXPECT_NEAR(l.points.at("pronasale").y(), 100.0, 0.1);
}

TEST(FaceLandmarks, FlatLipsAreFoundInOrder) {
  // A third of the relief: the lips stand out of the profile's chords by about a millimetre.
  const PhantomFace face(0.33);
  const FaceLandmarks l = find_face_landmarks(face.V, face.side_mask);
  const std::map<std::string, double> expected_z = {
      {"labrale superius", -24}, {"stomion", -31}, {"labrale inferius", -38}};
  for (const auto& [name, z] : expected_z) EXPECT_NEAR(l.points.at(name).z(), z, 2.0) << name;
  EXPECT_GT(l.points.at("subnasale").z(), -20.0);
  EXPECT_LT(l.points.at("subnasale").z(), -10.0);
}

TEST(FaceLandmarks, AFieldOfViewCutIsFoundBetweenSparseVertices) {
  // Rows of vertices every 4 mm in z, as on a model of 4 mm edges: three empty 1 mm profile bins between
  // neighbours. The cut at y = 96 flattens the profile from the nose's lower slope (y within the 3.5 mm plateau depth
  // of the front from z = -5.8) to the top (z = 58, the last row), found at the bins of the rows inside it (within a
  // row and half a bin); the lips below are found as on a fine sampling, within half a row more.
  constexpr double dz = 4.0;
  const PhantomFace face(1.0, dz, 96.0);
  const FaceLandmarks l = find_face_landmarks(face.V, face.side_mask);
  ASSERT_FALSE(std::isnan(l.clipped_from));
  EXPECT_NEAR(l.clipped_from, -5.8, dz + 0.5);
  EXPECT_NEAR(l.clipped_to, 58, dz + 0.5);
  for (const char* name : {"pronasale", "nasion", "glabella"})
    EXPECT_NE(std::find(l.estimated.begin(), l.estimated.end(), name), l.estimated.end()) << name;
  const std::map<std::string, double> expected_z = {
      {"subnasale", -14.6}, {"labrale superius", -24}, {"stomion", -31}, {"labrale inferius", -38}};
  for (const auto& [name, z] : expected_z) EXPECT_NEAR(l.points.at(name).z(), z, 1.5 + dz / 2) << name;
  EXPECT_NO_THROW(check_plausible(l, "test"));
}

TEST(FaceLandmarks, MouthCornersAreWhereTheLipsEnd) {
  // On the fine sampling and on rows 4 mm apart: the corners inside the lips' taper (20-26 mm from the midline), mirror
  // images of each other, on the mouth line under the upper lip (between the stomion and the labrale superius).
  for (const double dz : {0.5, 4.0}) {
    const PhantomFace face(1.0, dz);
    const FaceLandmarks l = find_face_landmarks(face.V, face.side_mask);
    ASSERT_TRUE(l.points.count("cheilion right") && l.points.count("cheilion left")) << dz;
    const Eigen::Vector3d right = l.points.at("cheilion right"), left = l.points.at("cheilion left");
    for (const double half_width : {PhantomFace::x0 - right.x(), left.x() - PhantomFace::x0}) {
      EXPECT_GE(half_width, 20.0) << dz;
      EXPECT_LE(half_width, 26.0) << dz;
    }
    EXPECT_NEAR(PhantomFace::x0 - right.x(), left.x() - PhantomFace::x0, 1.0) << dz;
    for (const Eigen::Vector3d& corner : {right, left}) {
      EXPECT_GT(corner.z(), l.points.at("stomion").z()) << dz;
      EXPECT_LT(corner.z(), l.points.at("labrale superius").z()) << dz;
    }
    EXPECT_NO_THROW(check_plausible(l, "test"));
  }
  // Lips too flat to show a mouth line: no corners rather than guessed ones.
  const PhantomFace flat(0.2);
  EXPECT_FALSE(find_face_landmarks(flat.V, flat.side_mask).points.count("cheilion left"));
}

TEST(FaceLandmarks, FeatureConstraintsSitOnTheLandmarks) {
  const PhantomFace face;
  const FaceLandmarks l = find_face_landmarks(face.V, face.side_mask);
  const std::map<std::string, double> values = {
      {"eyebrow line", 0.9}, {"below-nose line", 0.6}, {"middle lip line", 0.5}};
  const ConstraintSet set = feature_constraints(l, values, 2.0);
  ASSERT_EQ(set.constraints.size(), feature_specs().size());
  for (const Constraint& c : set.constraints) {
    ASSERT_TRUE(c.select.plane) << c.name;
    const PlaneSelection& p = *c.select.plane;
    if (c.field == 0) {
      EXPECT_EQ(c.value, 0.5);
      EXPECT_NEAR(p.point.x(), PhantomFace::x0, 0.5);
      EXPECT_EQ(p.normal, Eigen::Vector3d::UnitX());
    } else {
      EXPECT_EQ(c.value, values.at(c.name)) << c.name;
      EXPECT_EQ(p.normal, Eigen::Vector3d::UnitZ()) << c.name;
    }
  }
  EXPECT_THROW(feature_constraints(l, {}, 2.0), Error);  // the v features need the standard's values
}

TEST(FaceLandmarks, AFeatureThatSelectsNoVertexNamesItsLandmark) {
  // A tet at the nose tip: the mid-sagittal line selects it, the eyebrow line (at the glabella, far above) nothing.
  const PhantomFace face;
  const FaceLandmarks l = find_face_landmarks(face.V, face.side_mask);
  const Eigen::Vector3d tip = l.points.at("pronasale");
  Eigen::MatrixXd V(4, 3);
  V << tip.transpose(), (tip + Eigen::Vector3d(0.5, 0, 0)).transpose(), (tip + Eigen::Vector3d(0, 1, 0)).transpose(),
      (tip + Eigen::Vector3d(0, 0, 1)).transpose();
  const Eigen::MatrixXi T = (Eigen::MatrixXi(1, 4) << 0, 1, 2, 3).finished();
  const std::map<std::string, double> values = {
      {"eyebrow line", 0.9}, {"below-nose line", 0.6}, {"middle lip line", 0.5}};
  try {
    resolve_constraints(feature_constraints(l, values, 2.0), V, T, Eigen::VectorXi::Zero(4), "model.vtu");
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    const std::string what = e.what();
    for (const std::string& words : {std::string("model.vtu"), std::string("'eyebrow line' selects no vertex"),
                                     std::string("landmark 'glabella'"), std::string("found on the model")})
      EXPECT_NE(what.find(words), std::string::npos) << what << " lacks " << words;
  }
}

TEST(FaceLandmarks, AModelWithoutSkinOrLabelsIsAnError) {
  const PhantomFace face;
  EXPECT_THROW(find_face_landmarks(face.V, Eigen::VectorXi()), Error);
  EXPECT_THROW(find_face_landmarks(face.V, Eigen::VectorXi::Constant(face.V.rows(), side_bit(W0))), Error);
  // A face with no profile features at all (a plane): no nose tip to find above the rest, so no lips below it.
  Eigen::MatrixXd flat = face.V;
  flat.col(1).setConstant(80.0);
  EXPECT_THROW(find_face_landmarks(flat, face.side_mask), Error);
}

}  // namespace
}  // namespace facehex
