// The landmark finder under known warps of the bundled standard: the lips found on a warped standard are the warped
// lips of the standard (the answer is known: the warp applied to the landmarks found on the standard as it is).
#include <gtest/gtest.h>

#include "core/evaluation/correspondence_benchmark.h"
#include "core/face/face_landmarks.h"
#include "core/mesh/side_mask.h"

namespace facehex {
namespace {

TEST(LandmarkEquivariance, TheLipsFollowALongerNoseAForwardChinAndRandomWarps) {
  const StandardSetup standard = load_standard("artisynth-refface");
  const VolumeMesh& m = standard.mesh;
  const FaceLandmarks base = find_face_landmarks(m.V, side_mask_of(m));
  // random-1 shears the face so far that its forehead is the most anterior point of the middle of the profile: the
  // nose tip is not found there (the pronasale rule is not pitch-proof).
  for (const std::string warp : {"nose", "chin", "random-2", "random-3", "random-4"}) {
    const SmoothWarp w = face_warp(warp, m);
    const FaceLandmarks found = find_face_landmarks(w.apply_rows(m.V), side_mask_of(m));
    for (const std::string name : {"subnasale", "labrale superius", "stomion", "labrale inferius"}) {
      const Eigen::Vector3d truth = w.apply(base.points.at(name));
      // The standard's skin vertices are a few mm apart along the profile.
      EXPECT_LT((found.points.at(name) - truth).norm(), 3.0) << warp << ": " << name;
    }
  }
}

// A face swollen on one side (the skin's x range no longer centred on the face) with its nose deviated to the other,
// on the standard's sparse hex skin, moved 4 mm along x: the mid-sagittal plane is the face's mirror plane, not the
// middle of the skin's x range, and the lips are found on it.
TEST(LandmarkEquivariance, AnAsymmetricFaceKeepsTheMidSagittalPlaneOnItsMidline) {
  const StandardSetup standard = load_standard("artisynth-refface");
  const VolumeMesh& m = standard.mesh;
  const FaceLandmarks base = find_face_landmarks(m.V, side_mask_of(m));
  Eigen::Index widest = 0;
  m.V.col(0).maxCoeff(&widest);
  const SmoothWarp swollen = local_warp(m.V.row(widest).transpose(), Eigen::Vector3d(12, 0, 0), 15.0);
  const SmoothWarp deviated = local_warp(base.points.at("pronasale"), Eigen::Vector3d(-5, 0, 0), 10.0);
  Eigen::MatrixXd V = deviated.apply_rows(swollen.apply_rows(m.V));
  V.col(0).array() += 4.0;
  const FaceLandmarks found = find_face_landmarks(V, side_mask_of(m));
  EXPECT_NEAR(found.plane.x_at(0, 0), 4.0, 1.0);
  for (const std::string name : {"labrale superius", "stomion", "labrale inferius"}) {
    const Eigen::Vector3d truth = base.points.at(name) + Eigen::Vector3d(4, 0, 0);
    EXPECT_LT((found.points.at(name) - truth).norm(), 1.5) << name;
  }
}

// A mouth set to one side of the face's mirror plane (a bent midline: the lower face shifted along x, 6 mm at the
// mouth and fading over a few centimetres, the upper face not): the lips are read on the mouth's own midline, not
// beside it on the face's plane.
TEST(LandmarkEquivariance, TheLipsAreReadOnTheMouthsOwnMidline) {
  const StandardSetup standard = load_standard("artisynth-refface");
  const VolumeMesh& m = standard.mesh;
  const FaceLandmarks base = find_face_landmarks(m.V, side_mask_of(m));
  const SmoothWarp bent = local_warp(base.points.at("stomion"), Eigen::Vector3d(6, 0, 0), 35.0);
  const FaceLandmarks found = find_face_landmarks(bent.apply_rows(m.V), side_mask_of(m));
  EXPECT_LT(std::abs(found.plane.x), 3.0);  // the face's plane stays between the eyes
  for (const std::string name : {"subnasale", "labrale superius", "stomion", "labrale inferius"}) {
    const Eigen::Vector3d truth = bent.apply(base.points.at(name));
    EXPECT_LT((found.points.at(name) - truth).norm(), 1.5) << name;
  }
  // The mouth corners are traced from the mouth's midline and stay symmetric about it.
  const double corners_mid = 0.5 * (found.points.at("cheilion left").x() + found.points.at("cheilion right").x());
  EXPECT_NEAR(corners_mid, bent.apply(base.points.at("stomion")).x(), 1.5);
}

}  // namespace
}  // namespace facehex
