#include "core/face/face_landmarks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "core/face/automatic_constraints.h"
#include "core/fields/constraint_set.h"
#include "core/mesh/head_turn.h"
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

// Where PhantomFace's profile landmarks lie (z, mm).
const std::map<std::string, double> kPhantomProfileZ = {
    {"pronasale", 0},          {"subnasale", -14.6}, {"labrale superius", -24}, {"stomion", -31},
    {"labrale inferius", -38}, {"nasion", 25.8},     {"glabella", 40}};

// A phantom skin drawn through a piecewise-linear mid-sagittal profile, its (z, y) corners given from the top, with
// the relief fading sideways (25 mm) on a face curved sideways, sampled every 0.5 mm in x and z. roughness: each row
// of z is moved along y by a uniform random amount within +-roughness (seeded), as a 2-3 mm mesh roughens a profile.
struct ProfilePhantom {
  static constexpr double x0 = 0.0;
  Eigen::MatrixXd V;
  Eigen::VectorXi side_mask;

  ProfilePhantom(const std::vector<Eigen::Vector2d>& corners, double roughness, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> offset(-roughness, roughness);
    const double ztop = corners.front().x(), zbottom = corners.back().x();
    const int nx = 161, nz = static_cast<int>((ztop - zbottom) / 0.5) + 1;
    V.resize(nx * nz, 3);
    for (int k = 0; k < nz; ++k) {
      const double z = ztop - 0.5 * k, rough = offset(random);
      std::size_t c = 1;
      while (c + 1 < corners.size() && corners[c].x() > z) ++c;
      const double t = (z - corners[c - 1].x()) / (corners[c].x() - corners[c - 1].x());
      const double profile = corners[c - 1].y() + t * (corners[c].y() - corners[c - 1].y()) + rough;
      for (int i = 0; i < nx; ++i) {
        const double x = x0 - 40 + 0.5 * i;
        V.row(k * nx + i) << x, 60 + (profile - 60) * bump(x, x0, 25) - 0.01 * x * x, z;
      }
    }
    side_mask = Eigen::VectorXi::Constant(V.rows(), side_bit(W1));
  }
};

// The landmarks of a ProfilePhantom read on its own plane x = x0.
FaceLandmarks profile_landmarks(const std::vector<Eigen::Vector2d>& corners, double roughness, unsigned seed) {
  const ProfilePhantom face(corners, roughness, seed);
  LandmarkOptions options;
  options.mid_sagittal_plane = MidSagittalPlane{ProfilePhantom::x0, 0, 0};
  return find_face_landmarks(face.V, face.side_mask, options);
}

// A forehead, brow, nasion and a short nose above (tip at z 0, 2 mm in front of the lips: the chord from the upper lip
// to the tip is nearly vertical, as under a nose clipped by the field of view), the columella running back to the
// subnasale at z -10, a vertical upper lip below it down to z -20, the lips and the chin.
const std::vector<Eigen::Vector2d> kVerticalLip = {{60, 78},  {42, 85},    {30, 80},    {0, 90},   {-10, 84},
                                                   {-20, 84}, {-22, 87.5}, {-25, 88.3}, {-30, 84}, {-36, 87},
                                                   {-44, 80}, {-54, 86},   {-62, 76},   {-70, 70}};

TEST(FaceLandmarks, SubnasaleAtTheTopOfARoughVerticalLip) {
  // The lip from the subnasale down is vertical: only its top is where the columella meets it. On a rough profile
  // the walk up it must not stop at the first row that stands out by a few tenths of a millimetre.
  for (unsigned seed = 1; seed <= 12; ++seed) {
    const FaceLandmarks l = profile_landmarks(kVerticalLip, 0.4, seed);
    EXPECT_NEAR(l.points.at("subnasale").z(), -10, 1.5) << "seed " << seed;
  }
}

TEST(FaceLandmarks, TheMentonIsTheSkinUnderTheBonyMentonWhereTheCtGaveIt) {
  // kVerticalLip's chin recedes from y 86 at z -54 to y 76 at z -62: the vertical under a bony menton at y 80 leaves
  // the skin at z -58.8. Without the bone, the lowest skin point lies on the model's bottom edge: no menton.
  const ProfilePhantom face(kVerticalLip, 0.0, 1);
  LandmarkOptions options;
  options.mid_sagittal_plane = MidSagittalPlane{ProfilePhantom::x0, 0, 0};
  EXPECT_FALSE(find_face_landmarks(face.V, face.side_mask, options).points.count("menton"));
  for (const double turn_degrees : {0.0, 12.0}) {
    // The same face turned about the vertical axis through the origin, with its plane and its bone.
    const double c = std::cos(turn_degrees * M_PI / 180), s = std::sin(turn_degrees * M_PI / 180);
    const auto turned = [&](const Eigen::Vector3d& p) {
      return Eigen::Vector3d(c * p.x() + s * p.y(), -s * p.x() + c * p.y(), p.z());
    };
    Eigen::MatrixXd V = face.V;
    for (Eigen::Index v = 0; v < V.rows(); ++v) V.row(v) = turned(face.V.row(v).transpose()).transpose();
    LandmarkOptions with_bone;
    with_bone.mid_sagittal_plane = MidSagittalPlane{0, 0, 0, std::tan(turn_degrees * M_PI / 180), 0};
    with_bone.ct_landmarks = CtLandmarks{};
    with_bone.ct_landmarks->bony_menton = CtLandmark{turned(Eigen::Vector3d(ProfilePhantom::x0, 80, -50)), false};
    const FaceLandmarks l = find_face_landmarks(V, face.side_mask, with_bone);
    ASSERT_TRUE(l.points.count("menton")) << "turned " << turn_degrees;
    EXPECT_LT((l.points.at("menton") - turned(Eigen::Vector3d(ProfilePhantom::x0, 80, -58.8))).norm(), 0.6)
        << "turned " << turn_degrees << ": " << l.points.at("menton").transpose();
    EXPECT_FALSE(l.points.count("bony menton"));  // not a landmark of its own
  }
}

TEST(FaceLandmarks, ARippleUnderTheNoseIsNotTheLips) {
  // Under the nose tip (z 0) a ripple, a hollow at z -3 and a bump at z -5.5 standing out by 4 mm (a coarse scan's, or
  // where a field-of-view cut ends), then the subnasale (z -12), the upper lip (z -22), the stomion (z -28), the
  // lower lip (z -36) and the chin: the lips are read below the ripple, not one turn too high.
  const std::vector<Eigen::Vector2d> profile = {{60, 78},   {42, 85},  {30, 80},  {0, 90},     {-3, 85},
                                                {-5.5, 89}, {-12, 83}, {-22, 88}, {-28, 83.5}, {-36, 87},
                                                {-44, 80},  {-54, 86}, {-62, 76}, {-70, 70}};
  for (unsigned seed = 1; seed <= 6; ++seed) {
    const FaceLandmarks l = profile_landmarks(profile, 0.1, seed);
    EXPECT_NEAR(l.points.at("subnasale").z(), -12, 1.5) << "seed " << seed;
    EXPECT_NEAR(l.points.at("labrale superius").z(), -22, 1.5) << "seed " << seed;
    EXPECT_NEAR(l.points.at("stomion").z(), -28, 1.5) << "seed " << seed;
    EXPECT_NEAR(l.points.at("labrale inferius").z(), -36, 1.5) << "seed " << seed;
  }
}

TEST(FaceLandmarks, LabraleSuperiusIsTheFrontOfTheUpperLip) {
  // The upper lip leans forward from the subnasale to its front at z -19 and then falls steeply back to the stomion
  // (as on the bundled CT): the lip's turn, the profile's point furthest from the chord of its neighbours, can be the
  // top of the fall (z -21.5), but labrale superius is the front.
  const std::vector<Eigen::Vector2d> profile = {
      {60, 78},      {42, 85},  {30, 80},    {0, 95},   {-10, 84}, {-17, 86}, {-19, 86.4}, {-21.5, 85.6},
      {-22.5, 84.5}, {-24, 80}, {-26, 79.5}, {-32, 84}, {-40, 78}, {-50, 85}, {-60, 74},   {-70, 70}};
  for (unsigned seed = 1; seed <= 6; ++seed) {
    const ProfilePhantom face(profile, 0.1, seed);
    const FaceLandmarks l = find_face_landmarks(face.V, face.side_mask);
    EXPECT_NEAR(l.points.at("labrale superius").z(), -19, 1.0) << "seed " << seed;
  }
}

TEST(FaceLandmarks, AKnownMidSagittalPlaneIsUsed) {
  // The plane the segmentation found (here 1.2 mm beside the skin's own mirror plane) places the profile and the
  // mid-sagittal feature.
  const PhantomFace face;
  LandmarkOptions options;
  options.mid_sagittal_plane = MidSagittalPlane{PhantomFace::x0 + 1.2, 0, 0};
  const FaceLandmarks l = find_face_landmarks(face.V, face.side_mask, options);
  EXPECT_EQ(l.plane.x, PhantomFace::x0 + 1.2);
  EXPECT_EQ(l.plane_source, "model");
  EXPECT_EQ(find_face_landmarks(face.V, face.side_mask).plane_source, "skin");
  for (const char* name : {"pronasale", "subnasale", "stomion", "nasion", "glabella"})
    EXPECT_EQ(l.points.at(name).x(), PhantomFace::x0 + 1.2) << name;
}

// The landmarks of `face` tilted by `degrees` about the y axis through (x0, 0) (x towards -z), read on the plane the
// segmentation would give it: leaning so.
FaceLandmarks tilted_phantom_landmarks(PhantomFace face, double degrees) {
  const double tilt = degrees * M_PI / 180, c = std::cos(tilt), s = std::sin(tilt);
  for (Eigen::Index v = 0; v < face.V.rows(); ++v) {
    const double dx = face.V(v, 0) - PhantomFace::x0, z = face.V(v, 2);
    face.V(v, 0) = PhantomFace::x0 + c * dx - s * z;
    face.V(v, 2) = s * dx + c * z;
  }
  LandmarkOptions options;
  options.mid_sagittal_plane = MidSagittalPlane{PhantomFace::x0, -std::tan(tilt), 0};
  return find_face_landmarks(face.V, face.side_mask, options);
}

TEST(FaceLandmarks, AHeadTiltedTowardsAShoulderIsReadOnItsLeaningPlane) {
  // The phantom tilted by 12 degrees about the y axis through (x0, 0): its midline runs along x = x0 - tan(12) z, the
  // lips 6-8 mm beside the nose's vertical. With the plane the segmentation found (leaning so), every profile landmark
  // lies where the tilt moved it, on that plane.
  const double tilt = 12 * M_PI / 180, c = std::cos(tilt), s = std::sin(tilt);
  const FaceLandmarks l = tilted_phantom_landmarks(PhantomFace(), 12);
  for (const auto& [name, z] : kPhantomProfileZ) {
    ASSERT_TRUE(l.points.count(name)) << name;
    const Eigen::Vector3d p = l.points.at(name);
    EXPECT_NEAR(p.z(), c * z, 1.5) << name;
    EXPECT_NEAR(p.x(), PhantomFace::x0 - s * z, 1.5) << name;
  }
  // The mid-sagittal feature's plane leans with it.
  const ConstraintSet set =
      feature_constraints(l, {{"eyebrow line", 0.9}, {"below-nose line", 0.6}, {"middle lip line", 0.5}}, 2.0);
  const PlaneSelection& mid = *set.constraints.front().select.plane;
  EXPECT_NEAR(mid.normal.dot(Eigen::Vector3d(-std::tan(tilt), 0, 1).normalized()), 0, 1e-12);
}

TEST(FaceLandmarks, ATiltedHeadsMouthCornersAreWhereItsLipsEnd) {
  // The phantom with lips of 0.6 the relief (a closed mouth's line is faint), upright and tilted towards either
  // shoulder about the y axis through (x0, 0), its mouth line with it: turned back, the corners lie inside the lips'
  // taper (20-26 mm from the midline), mirror images of each other, on the mouth line, as on the upright face (read
  // down the model's columns instead, which cross a tilted mouth line obliquely, one corner falls short of the taper).
  for (const double degrees : {0.0, 12.0, -20.0, 20.0}) {
    const double tilt = degrees * M_PI / 180, c = std::cos(tilt), s = std::sin(tilt);
    const FaceLandmarks l = tilted_phantom_landmarks(PhantomFace(0.6), degrees);
    ASSERT_TRUE(l.points.count("cheilion right") && l.points.count("cheilion left")) << degrees;
    std::vector<double> half_widths;
    for (const char* name : {"cheilion right", "cheilion left"}) {
      const Eigen::Vector3d p = l.points.at(name);
      const double dx = p.x() - PhantomFace::x0, upright_x = c * dx + s * p.z(), upright_z = -s * dx + c * p.z();
      half_widths.push_back(std::abs(upright_x));
      EXPECT_GE(half_widths.back(), 20.0) << degrees << " " << name;
      EXPECT_LE(half_widths.back(), 26.0) << degrees << " " << name;
      EXPECT_GT(upright_z, -31.0) << degrees << " " << name;
      EXPECT_LT(upright_z, -24.0) << degrees << " " << name;
    }
    EXPECT_NEAR(half_widths[0], half_widths[1], 1.0) << degrees;
  }
}

TEST(FaceLandmarks, AHeadTurnedAboutTheVerticalIsReadInItsHeadFrame) {
  // The phantom turned about the vertical line x = x0, y = 60 by 20 degrees (its face looks towards (sin, cos, 0) of
  // 20 degrees): with the plane turned so, every landmark is the upright phantom's turned, the cheilions included,
  // within a sample (the turned vertices' rounding moves some across the profile band's edge).
  const PhantomFace upright;
  const FaceLandmarks straight = find_face_landmarks(upright.V, upright.side_mask);
  for (const double degrees : {20.0, -12.0}) {
    HeadTurn turn;
    turn.degrees = degrees;  // to_model turns the upright phantom's +y towards (sin, cos) of `degrees`
    turn.axis = Eigen::Vector2d(PhantomFace::x0, 60);
    PhantomFace face;
    for (Eigen::Index v = 0; v < face.V.rows(); ++v)
      face.V.row(v) = turn.to_model(upright.V.row(v).transpose()).transpose();
    LandmarkOptions options;
    MidSagittalPlane plane;
    plane.x = PhantomFace::x0;
    plane.y = 60;
    plane.turn = std::tan(degrees * M_PI / 180);
    options.mid_sagittal_plane = plane;
    const FaceLandmarks l = find_face_landmarks(face.V, face.side_mask, options);
    EXPECT_EQ(l.plane.turn, plane.turn);
    ASSERT_EQ(l.points.size(), straight.points.size()) << degrees;
    for (const auto& [name, p] : straight.points) {
      ASSERT_TRUE(l.points.count(name)) << name;
      EXPECT_LT((l.points.at(name) - turn.to_model(p)).norm(), 0.6) << name << " at " << degrees << " degrees";
    }
    // The mid-sagittal feature's plane is the turned plane: the turned nose tip's direction lies in it.
    const ConstraintSet set =
        feature_constraints(l, {{"eyebrow line", 0.9}, {"below-nose line", 0.6}, {"middle lip line", 0.5}}, 2.0);
    const PlaneSelection& mid = *set.constraints.front().select.plane;
    const Eigen::Vector3d forward(std::sin(degrees * M_PI / 180), std::cos(degrees * M_PI / 180), 0);
    EXPECT_NEAR(mid.normal.dot(forward), 0, 1e-12);
    EXPECT_NEAR(mid.normal.dot(l.points.at("pronasale") - mid.point), 0, 1e-9);
    // The same landmarks given (a file): their plane is the model's, turned, through the given pronasale.
    const FaceLandmarks given = landmarks_from(named_landmarks(l), "given.json");
    FaceLandmarks used;
    const std::map<std::string, double> values = {
        {"eyebrow line", 0.9}, {"below-nose line", 0.6}, {"middle lip line", 0.5}};
    const ConstraintSet from_file =
        landmark_feature_constraints(face.V, face.side_mask, options, values, 2.0, &used, &given);
    EXPECT_EQ(used.plane.turn, plane.turn);
    const PlaneSelection& given_mid = *from_file.constraints.front().select.plane;
    EXPECT_NEAR(given_mid.normal.dot(forward), 0, 1e-12);
    EXPECT_NEAR(given_mid.normal.dot(given.points.at("pronasale") - given_mid.point), 0, 1e-9);
  }
}

TEST(FaceLandmarks, APitchedHeadIsReadInItsHeadFrameAndItsFeaturesArePitchedWithIt) {
  // The phantom pitched about the lateral line y = 60, z = 0 (chin raised by 14 degrees, lowered by 10), and turned by
  // 8: with the plane carrying the pitch, every landmark is the upright phantom's moved with it, and the eyebrow,
  // below-nose and lip lines lie on planes horizontal in the head frame.
  const PhantomFace upright;
  const FaceLandmarks straight = find_face_landmarks(upright.V, upright.side_mask);
  for (const double pitch : {14.0, -10.0}) {
    HeadTurn turn;
    turn.degrees = 8;
    turn.axis = Eigen::Vector2d(PhantomFace::x0, 60);
    turn.pitch = pitch;
    PhantomFace face;
    for (Eigen::Index v = 0; v < face.V.rows(); ++v)
      face.V.row(v) = turn.to_model(upright.V.row(v).transpose()).transpose();
    MidSagittalPlane head_plane;
    head_plane.x = PhantomFace::x0;
    head_plane.y = 60;
    LandmarkOptions options;
    options.mid_sagittal_plane = turn.to_model(head_plane);
    EXPECT_EQ(options.mid_sagittal_plane->pitch, pitch);
    const FaceLandmarks l = find_face_landmarks(face.V, face.side_mask, options);
    ASSERT_EQ(l.points.size(), straight.points.size()) << pitch;
    for (const auto& [name, p] : straight.points) {
      ASSERT_TRUE(l.points.count(name)) << name;
      EXPECT_LT((l.points.at(name) - turn.to_model(p)).norm(), 0.6) << name << " at " << pitch << " degrees";
    }
    // Read in the model's own frame instead (no pitch known), some landmark lies further off.
    LandmarkOptions unpitched = options;
    unpitched.mid_sagittal_plane->pitch = 0;
    double worst = 0;
    try {
      const FaceLandmarks wrong = find_face_landmarks(face.V, face.side_mask, unpitched);
      for (const auto& [name, p] : straight.points)
        if (wrong.points.count(name)) worst = std::max(worst, (wrong.points.at(name) - turn.to_model(p)).norm());
    } catch (const Error&) {
      worst = std::numeric_limits<double>::infinity();
    }
    EXPECT_GT(worst, 1.0) << pitch;  // beyond the 0.6 mm the head frame meets
    const ConstraintSet set =
        feature_constraints(l, {{"eyebrow line", 0.9}, {"below-nose line", 0.6}, {"middle lip line", 0.5}}, 2.0);
    const Eigen::Vector3d up = turn.to_model(Eigen::Vector3d::UnitZ()) - turn.to_model(Eigen::Vector3d::Zero());
    for (const Constraint& c : set.constraints) {
      if (c.field == 1) {
        EXPECT_LT((c.select.plane->normal - up).norm(), 1e-12) << c.name;
      }
    }
  }
}

TEST(FaceLandmarks, PhantomLandmarksWithinOneAndAHalfMillimetres) {
  const PhantomFace face;
  const FaceLandmarks l = find_face_landmarks(face.V, face.side_mask);
  constexpr double tolerance = 1.5;  // mm: 1 mm profile bins on a 0.5 mm sampling
  EXPECT_NEAR(l.plane.x, PhantomFace::x0, 0.5);
  for (const auto& [name, z] : kPhantomProfileZ) {
    ASSERT_TRUE(l.points.count(name)) << name;
    const Eigen::Vector3d p = l.points.at(name);
    EXPECT_NEAR(p.z(), z, tolerance) << name;
    EXPECT_NEAR(p.x(), PhantomFace::x0, 3.0) << name;  // within the profile band
  }
  EXPECT_NEAR(l.points.at("pronasale").y(), 100.0, 0.1);
}

TEST(FaceLandmarks, AScanEndingJustAboveTheNasionHasItsGlabellaEstimated) {
  // The phantom cut off at z = 30, 4 mm above its nasion and below its brow (z = 40): no brow to find, so the glabella
  // is placed 12 mm above the nasion (held below the model's top) and marked estimated; the rest is found as before.
  const PhantomFace whole;
  std::vector<int> below;
  for (int v = 0; v < whole.V.rows(); ++v)
    if (whole.V(v, 2) <= 30) below.push_back(v);
  const Eigen::MatrixXd V = whole.V(below, Eigen::all);
  const Eigen::VectorXi side_mask = whole.side_mask(below);
  const FaceLandmarks l = find_face_landmarks(V, side_mask);
  EXPECT_EQ(l.estimated, std::vector<std::string>{"glabella"});
  EXPECT_NEAR(l.points.at("glabella").z(), 29, 1e-9);
  EXPECT_NEAR(l.points.at("glabella").x(), PhantomFace::x0, 0.5);
  for (const auto& [name, z] : kPhantomProfileZ) {
    if (name == "glabella") continue;
    EXPECT_NEAR(l.points.at(name).z(), z, 1.5) << name;
  }
  EXPECT_NO_THROW(check_plausible(l, "test"));
}

TEST(FaceLandmarks, TheProfileIsReadUnderAnObjectOnTheSkin) {
  // A strap 4 mm thick over the phantom's brow (z 32 to 46), its edges spread over 3 mm either side as the
  // segmentation's blurred skin spreads them; the segmentation's reading of it (core/segment/skin_objects.h) gives the
  // skin under it, the bare phantom's profile. Without it the glabella is read on the strap's front.
  PhantomFace face;
  const auto on = [](double z) { return 1 / (1 + std::exp(-z * 1.5)); };  // 0 to 1 over about 3 mm either side
  const auto profile_at = [](const PhantomFace& f, double z) {
    double y = -std::numeric_limits<double>::infinity();
    for (int v = 0; v < f.V.rows(); ++v)
      if (std::abs(f.V(v, 0) - PhantomFace::x0) < 0.25 && std::abs(f.V(v, 2) - z) < 0.25) y = std::max(y, f.V(v, 1));
    return y;
  };
  SkinObject strap{32, 46, 4, 4, {}};
  for (double z = 27; z <= 51; z += 0.5) strap.skin.emplace_back(z, profile_at(face, z));
  for (int v = 0; v < face.V.rows(); ++v) {
    const double z = face.V(v, 2);
    face.V(v, 1) += 4 * on(z - 32) * on(46 - z);
  }
  LandmarkOptions options;
  options.mid_sagittal_plane = MidSagittalPlane{PhantomFace::x0, 0, 0};
  const FaceLandmarks on_strap = find_face_landmarks(face.V, face.side_mask, options);
  EXPECT_GT(on_strap.points.at("glabella").y(), strap.skin[26].y() + 3);  // z = 40: on the strap's front
  options.ct_landmarks = CtLandmarks{};
  options.ct_landmarks->skin_objects = {strap};
  const FaceLandmarks l = find_face_landmarks(face.V, face.side_mask, options);
  const Eigen::Vector3d g = l.points.at("glabella");
  EXPECT_NEAR(g.z(), 40, 1.5);
  EXPECT_NEAR(g.y(), profile_at(face, 40) - 4, 0.3);  // the bare phantom's front there
  EXPECT_NE(std::find(l.estimated.begin(), l.estimated.end(), "glabella"), l.estimated.end());
  EXPECT_EQ(std::find(l.estimated.begin(), l.estimated.end(), "nasion"), l.estimated.end());  // below the strap's reach
  EXPECT_NEAR(l.points.at("nasion").z(), kPhantomProfileZ.at("nasion"), 1.5);
  EXPECT_NE(landmarks_text(l, "").find("an object lies on the skin's front from z = 32.0 to 46.0 mm, 4.0 mm thick"),
            std::string::npos)
      << landmarks_text(l, "");
}

TEST(FaceLandmarks, ACutPastTheNasionHasTheNasionPlacedByProportions) {
  // The field of view cuts the face flat from the nose tip (z 0) to z 76, and the forehead above recedes behind the
  // cut with a hollow at z 80: the cut ends well below the top (z 100), but the hollow lies 90 mm above the
  // subnasale (z -10), further than any adult nasion. The cut reached past the nasion: the pronasale, nasion and
  // glabella are placed by proportions on the cut (15, 55 and 67 mm above the subnasale), not at the hollow.
  std::vector<Eigen::Vector2d> corners = {{100, 80}, {86, 80}, {80, 76}, {76, 90}};
  corners.insert(corners.end(), kVerticalLip.begin() + 3, kVerticalLip.end());
  const FaceLandmarks l = profile_landmarks(corners, 0.0, 1);
  EXPECT_NEAR(l.clipped_to, 76, 1.5);
  const double sn = l.points.at("subnasale").z();
  EXPECT_NEAR(sn, -10, 1.5);
  for (const auto& [name, above] : std::map<std::string, double>{{"pronasale", 15}, {"nasion", 55}, {"glabella", 67}}) {
    EXPECT_NE(std::find(l.estimated.begin(), l.estimated.end(), name), l.estimated.end()) << name;
    EXPECT_NEAR(l.points.at(name).z(), sn + above, 1e-9) << name;
  }
}

TEST(FaceLandmarks, ALongNosesNasionIsTheHollowBelowTheBrow) {
  // The phantom's face above the nose tip stretched to twice its height: the nasion 52 mm above the tip (an adult
  // man's nose can be that long) and the brow 80 mm, on a dorsum without and with a hump (1.5 mm at z 24). Looked for
  // only up to 45 mm above the tip, the nasion was read on the dorsum, 7 mm low.
  for (const double hump : {0.0, 1.5}) {
    PhantomFace face;
    for (int v = 0; v < face.V.rows(); ++v)
      if (face.V(v, 2) > 0) {
        face.V(v, 2) *= 2;
        face.V(v, 1) += hump * bump(face.V(v, 2), 24, 3) * bump(face.V(v, 0) - PhantomFace::x0, 0, 8);
      }
    const FaceLandmarks l = find_face_landmarks(face.V, face.side_mask);
    EXPECT_NEAR(l.points.at("pronasale").z(), 0, 1.5) << hump;
    EXPECT_NEAR(l.points.at("nasion").z(), 2 * kPhantomProfileZ.at("nasion"), 1.5) << hump;
    // The stretched brow is flat over 16 mm, and the glabella, its middle within 30 mm of the nasion, lies low in it.
    EXPECT_NEAR(l.points.at("glabella").z(), 2 * kPhantomProfileZ.at("glabella"), 2.5) << hump;
    EXPECT_TRUE(l.estimated.empty()) << hump;
    EXPECT_NO_THROW(check_plausible(l, "test"));
  }
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

// A nose clipped by the field of view back to the lips' level: the cut (y 89.3, z -1 to 24) stands 2.8 mm in front of
// the subnasale's hollow (z -5 to -20) and 1 mm in front of the upper lip (z -22 to -25), both within the plateau depth
// that a coarse model's roughness needs; the forehead above, with the nasion's hollow at z 30.
const std::vector<Eigen::Vector2d> kClippedToTheLips = {{60, 84},   {42, 85},    {30, 80},    {24, 89.3},  {-1, 89.3},
                                                        {-5, 86.5}, {-20, 86.5}, {-22, 88.3}, {-25, 88.3}, {-30, 84},
                                                        {-36, 87},  {-44, 80},   {-54, 86},   {-62, 76},   {-70, 70}};

// What a profile of kClippedToTheLips (its chin aside) reads: the cut at its flat front, the nose tip estimated there,
// the lips, the subnasale and the nasion where the profile has them.
void expect_clipped_to_the_lips(const FaceLandmarks& l, unsigned seed) {
  EXPECT_NEAR(l.clipped_from, -4, 1.5) << seed;
  EXPECT_NEAR(l.clipped_to, 24, 1.5) << seed;
  EXPECT_EQ(l.estimated, std::vector<std::string>{"pronasale"}) << seed;
  const std::map<std::string, double> expected_z = {
      {"subnasale", -5}, {"labrale superius", -23.5}, {"stomion", -30}, {"labrale inferius", -36}, {"nasion", 30}};
  for (const auto& [name, z] : expected_z) EXPECT_NEAR(l.points.at(name).z(), z, 2.0) << name << ", seed " << seed;
}

TEST(FaceLandmarks, ACutLevelWithTheLipsEndsAtTheFlatFront) {
  for (unsigned seed : {1u, 2u, 3u}) expect_clipped_to_the_lips(profile_landmarks(kClippedToTheLips, 0.2, seed), seed);
}

// A nose clipped by a field of view that leans back 6 degrees in the head frame (a head pitched in the scanner):
// the cut runs from the top (z 60, y 96.3) down to the nose's lowest cut point (z 0, y 90), 6.3 mm behind its top.
// Behind an upright front its plateau ends 24 mm above the nose; along its own line it reaches down to where the
// nose's underside falls the plateau's depth (3.5 mm) behind that line (z -7), and the lips below are found as under
// an upright cut.
TEST(FaceLandmarks, ACutLeaningInTheHeadFrameIsFollowedDownToTheNose) {
  std::vector<Eigen::Vector2d> corners = {{60, 96.3}};
  corners.insert(corners.end(), kVerticalLip.begin() + 3, kVerticalLip.end());
  for (unsigned seed : {1u, 2u, 3u}) {
    const FaceLandmarks l = profile_landmarks(corners, 0.2, seed);
    EXPECT_NEAR(l.clipped_from, -7, 1.5) << seed;
    EXPECT_NEAR(l.clipped_to, 60, 1.5) << seed;
    const std::map<std::string, double> expected_z = {
        {"subnasale", -10}, {"labrale superius", -24}, {"stomion", -30}, {"labrale inferius", -36}};
    for (const auto& [name, z] : expected_z) EXPECT_NEAR(l.points.at(name).z(), z, 2.0) << name << ", seed " << seed;
  }
}

// The same clipped nose above a chin that stands 4.7 mm in front of the cut (z -54, y 94: a prominent chin of a head
// pitched chin-up under a field of view that clips the nose): the chin is the profile's most anterior point and the
// cut lies deeper behind it than a plateau's depth, but the chin lies in the face's lowest third, where no nose tip
// does; the nose and the lips are read above it as without it.
TEST(FaceLandmarks, AChinInFrontOfAClippedNoseIsNotTakenForTheNose) {
  std::vector<Eigen::Vector2d> corners = kClippedToTheLips;
  for (auto& corner : corners)
    if (corner.x() == -54) corner.y() = 94;
  for (unsigned seed : {1u, 2u, 3u}) {
    const FaceLandmarks l = profile_landmarks(corners, 0.2, seed);
    expect_clipped_to_the_lips(l, seed);
    EXPECT_NEAR(l.points.at("pogonion").z(), -54, 2.0) << seed;
  }
}

TEST(FaceLandmarks, ACutThatTookTheLipsIsNamedInTheError) {
  // The same cut carried down to z -40: the lips lie inside it, and the error says where the cut is.
  std::vector<Eigen::Vector2d> corners(kClippedToTheLips.begin(), kClippedToTheLips.begin() + 4);
  corners.insert(corners.end(), {{-40, 89.3}, {-44, 80}, {-54, 86}, {-62, 76}, {-70, 70}});
  try {
    profile_landmarks(corners, 0.0, 1);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("field of view cuts the face flat (z "), std::string::npos) << what;
    EXPECT_NE(what.find("--landmarks FILE"), std::string::npos) << what;
  }
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

// A model with an open mouth and open eyes (rims of walls on no side, LandmarkOptions::opening_rims): their corners
// are the rims' ends towards -x and +x, as the standard's are, found (not estimated), instead of the mouth line read
// beside the opening; the largest rim of a name with an eye's or a mouth's width and place is the opening, and a rim
// elsewhere names no landmark. Turned with the
// head, the ends are taken in its head frame.
TEST(FaceLandmarks, TheCornersOfOpenEyesAndAnOpenMouthAreTheirRimsEnds) {
  const PhantomFace upright;
  const FaceLandmarks found = find_face_landmarks(upright.V, upright.side_mask);
  const double x0 = PhantomFace::x0;
  const Eigen::Vector3d stomion = found.points.at("stomion"), pronasale = found.points.at("pronasale");
  // An ellipse of points about `centre` in the x-z plane, half widths a (x) and b (z): its ends are centre -+ a x.
  const auto rim = [](const Eigen::Vector3d& centre, double a, double b, int n) {
    Eigen::MatrixXd points(n, 3);
    for (int i = 0; i < n; ++i) {
      const double t = 2 * M_PI * (i + 0.25) / n;  // no sample exactly at an end but the two placed below
      points.row(i) = (centre + Eigen::Vector3d(a * std::cos(t), -1, b * std::sin(t))).transpose();
    }
    points.row(0) = (centre - Eigen::Vector3d(a, 0, 0)).transpose();
    points.row(1) = (centre + Eigen::Vector3d(a, 0, 0)).transpose();
    return points;
  };
  const Eigen::Vector3d mouth = stomion + Eigen::Vector3d(0, -2, 0);
  const Eigen::Vector3d right_eye = pronasale + Eigen::Vector3d(-32, -20, 25),
                        left_eye = right_eye + Eigen::Vector3d(64, 0, 0);
  LandmarkOptions options;
  options.opening_rims = {rim(mouth, 24, 4, 40),
                          rim(mouth + Eigen::Vector3d(0, 0, 1), 5, 2, 10),  // and a smaller piece
                          rim(right_eye, 14, 4, 30), rim(left_eye, 14, 4, 30),
                          rim(pronasale + Eigen::Vector3d(0, 0, -200), 30, 5, 30),  // far below: no landmark
                          // where a model's sides meet at its top cut, beside the right eye: more rim vertices than the
                          // eye's, but neither an eye's width nor its place
                          rim(pronasale + Eigen::Vector3d(-72, -80, 60), 0.4, 0.5, 40)};
  const FaceLandmarks l = find_face_landmarks(upright.V, upright.side_mask, options);
  const std::map<std::string, Eigen::Vector3d> ends = {{"cheilion right", mouth - Eigen::Vector3d(24, 0, 0)},
                                                       {"cheilion left", mouth + Eigen::Vector3d(24, 0, 0)},
                                                       {"exocanthion right", right_eye - Eigen::Vector3d(14, 0, 0)},
                                                       {"endocanthion right", right_eye + Eigen::Vector3d(14, 0, 0)},
                                                       {"endocanthion left", left_eye - Eigen::Vector3d(14, 0, 0)},
                                                       {"exocanthion left", left_eye + Eigen::Vector3d(14, 0, 0)}};
  for (const auto& [name, end] : ends) {
    ASSERT_TRUE(l.points.count(name)) << name;
    EXPECT_LT((l.points.at(name) - end).norm(), 1e-9) << name;
    EXPECT_EQ(std::count(l.estimated.begin(), l.estimated.end(), name), 0) << name;
  }
  EXPECT_EQ(l.points.at("stomion"), stomion);  // the profile is read as without openings
  // Turned by 15 degrees about the vertical through x0, y 60, with the openings: the same ends, turned.
  HeadTurn turn;
  turn.degrees = 15;
  turn.axis = Eigen::Vector2d(x0, 60);
  PhantomFace face;
  for (Eigen::Index v = 0; v < face.V.rows(); ++v)
    face.V.row(v) = turn.to_model(upright.V.row(v).transpose()).transpose();
  LandmarkOptions turned = options;
  for (Eigen::MatrixXd& r : turned.opening_rims)
    for (Eigen::Index i = 0; i < r.rows(); ++i) r.row(i) = turn.to_model(r.row(i).transpose()).transpose();
  MidSagittalPlane plane;
  plane.x = x0;
  plane.y = 60;
  plane.turn = std::tan(15 * M_PI / 180);
  turned.mid_sagittal_plane = plane;
  const FaceLandmarks t = find_face_landmarks(face.V, face.side_mask, turned);
  for (const auto& [name, end] : ends) {
    ASSERT_TRUE(t.points.count(name)) << name;
    EXPECT_LT((t.points.at(name) - turn.to_model(end)).norm(), 1e-9) << name;
  }
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

// The message check_plausible throws for `l`, or "" when it accepts it.
std::string implausibility(const FaceLandmarks& l) {
  try {
    check_plausible(l, "give them with --landmarks FILE");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(FaceLandmarks, TheLandmarksAModelCarriesFromItsCtAreListedWithTheirStatusAndChecked) {
  const PhantomFace face;
  LandmarkOptions options;
  CtLandmarks found;
  Tragi& tragi = found.tragi;
  tragi[0] = CtLandmark{Eigen::Vector3d(PhantomFace::x0 - 70, -10, 0), false};
  tragi[1] = CtLandmark{Eigen::Vector3d(PhantomFace::x0 + 70, -10, 0), true};
  found.eye_corners[1] = CtLandmark{Eigen::Vector3d(PhantomFace::x0 - 45, 60, 30), false};
  found.eye_corners[3] = CtLandmark{Eigen::Vector3d(PhantomFace::x0 + 45, 60, 30), true};
  found.stomion = CtLandmark{Eigen::Vector3d(PhantomFace::x0, 70, -35), false};
  found.mouth_corners[0] = CtLandmark{Eigen::Vector3d(PhantomFace::x0 - 26, 62, -37), false};
  options.ct_landmarks = found;
  const FaceLandmarks l = find_face_landmarks(face.V, face.side_mask, options);
  // The CT's mouth corner in place of the skin's; the other, not seen in the CT, the skin's.
  const FaceLandmarks on_skin = find_face_landmarks(face.V, face.side_mask);
  EXPECT_EQ(l.points.at("cheilion right"), found.mouth_corners[0]->point);
  EXPECT_NE(on_skin.points.at("cheilion right"), found.mouth_corners[0]->point);
  EXPECT_EQ(l.points.at("cheilion left"), on_skin.points.at("cheilion left"));
  EXPECT_EQ(l.points.at("tragus right"), tragi[0]->point);
  EXPECT_EQ(l.points.at("tragus left"), tragi[1]->point);
  for (const NamedLandmark& n : named_landmarks(l)) {
    if (n.name == "tragus right") {
      EXPECT_EQ(n.status, LandmarkStatus::found);
    }
    if (n.name == "tragus left") {
      EXPECT_EQ(n.status, LandmarkStatus::estimated);
    }
  }
  EXPECT_EQ(l.points.at("exocanthion left"), found.eye_corners[3]->point);
  EXPECT_FALSE(l.points.count("endocanthion left"));        // not seen
  EXPECT_EQ(l.points.at("stomion"), found.stomion->point);  // the CT's in place of the skin's
  EXPECT_NE(find_face_landmarks(face.V, face.side_mask).points.at("stomion"), found.stomion->point);
  EXPECT_NE(std::find(l.estimated.begin(), l.estimated.end(), "exocanthion left"), l.estimated.end());
  EXPECT_EQ(std::find(l.estimated.begin(), l.estimated.end(), "exocanthion right"), l.estimated.end());
  EXPECT_EQ(implausibility(l), "");
  // Outer eye corners 125 mm apart (wider than any adult's), an eye 49 mm wide: errors naming the corner.
  FaceLandmarks wide = l;
  wide.points["exocanthion left"].x() = PhantomFace::x0 + 80;
  EXPECT_NE(implausibility(wide).find("implausible exocanthion: the distance exocanthion left - exocanthion right is "
                                      "125.0 mm"),
            std::string::npos)
      << implausibility(wide);
  wide.points["exocanthion left"].x() = PhantomFace::x0 + 50;
  wide.points["endocanthion left"] = Eigen::Vector3d(PhantomFace::x0 + 1, 60, 30);
  EXPECT_NE(implausibility(wide).find("implausible exocanthion left: the distance endocanthion left - exocanthion "
                                      "left is 49.0 mm"),
            std::string::npos)
      << implausibility(wide);
  // Tragi 50 mm apart (no adult head is so narrow), one above the glabella, both 140 mm further back (no head is so
  // deep): each is an error naming the tragus and the remedy.
  FaceLandmarks narrow = l;
  narrow.points["tragus left"].x() = PhantomFace::x0 + 20;
  narrow.points["tragus right"].x() = PhantomFace::x0 - 30;
  EXPECT_NE(implausibility(narrow).find("implausible tragus: the distance tragus left - tragus right is 50.0 mm"),
            std::string::npos)
      << implausibility(narrow);
  // The tragi's sides swapped: the left one lies across the plane, on the right's side; with a scan frame whose
  // patient's left is at -x (a DICOM series), the error names them as the patient's.
  FaceLandmarks swapped = l;
  std::swap(swapped.points["tragus left"], swapped.points["tragus right"]);
  EXPECT_NE(implausibility(swapped).find("implausible tragus left: it lies 70.5 mm across the mid-sagittal plane, on "
                                         "the tragus right's side"),
            std::string::npos)
      << implausibility(swapped);
  swapped.scan_frame.rotation = Eigen::Vector3d(-1, -1, 1).asDiagonal();
  EXPECT_NE(implausibility(swapped).find("implausible tragus right: it lies 70.5 mm across the mid-sagittal plane, on "
                                         "the tragus left's side"),
            std::string::npos)
      << implausibility(swapped);
  FaceLandmarks high = l;
  high.points["tragus left"].z() = 60;
  EXPECT_NE(implausibility(high).find("implausible tragus left: it lies above the glabella"), std::string::npos)
      << implausibility(high);
  FaceLandmarks far = l;
  far.points["tragus right"].y() = far.points["tragus left"].y() = -150;
  EXPECT_NE(implausibility(far).find("implausible tragus left: the distance nasion - tragus left"), std::string::npos)
      << implausibility(far);
  EXPECT_NE(implausibility(far).find("--landmarks FILE"), std::string::npos);
  EXPECT_NE(implausibility(far).find("--posterior-cut places it"), std::string::npos);
  // Without them, no tragus.
  EXPECT_FALSE(find_face_landmarks(face.V, face.side_mask).points.count("tragus left"));
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
