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
    const SmoothWarp w = standard_warp(warp, m);
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

}  // namespace
}  // namespace facehex
