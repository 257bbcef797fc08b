// The landmarks of the bundled sample patient (resources/patients/headsq), whose CT cuts the front of the face flat.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/face/face_landmarks.h"
#include "core/fields/constraint_set.h"
#include "core/io/mesh_io.h"
#include "core/util/resources.h"

namespace facehex {
namespace {

// Its mid-sagittal skin profile (most anterior y per z, measured once, and checked against a front render, where
// the mouth slit is at z ~ 37-40): lower lip at z 25-28 (y 162.7), lip contact at z 37 (159.3), upper lip at z 49
// (173.9), the dip below the nose at z 55-56 (171.5), then from z 64 to the top a plateau at y 182-185.5 where the
// field of view cut the nose and forehead.
TEST(BundledPatient, LandmarksOfAClippedProfileAreFoundBelowTheCutAndEstimatedInIt) {
  const VolumeMesh patient = read_volume_mesh(default_patient().mesh);
  const FaceLandmarks l = find_face_landmarks(patient.V, side_mask_of(patient));
  ASSERT_FALSE(std::isnan(l.clipped_from));
  EXPECT_NEAR(l.clipped_from, 64, 2.0);
  EXPECT_GT(l.clipped_to, 125);
  EXPECT_NEAR(l.points.at("labrale inferius").z(), 27, 2.0);
  EXPECT_NEAR(l.points.at("stomion").z(), 37.5, 2.0);
  EXPECT_NEAR(l.points.at("labrale superius").z(), 49, 2.0);
  EXPECT_NEAR(l.points.at("subnasale").z(), 58.5, 2.0);  // where the columella meets the lip (tests/data/landmarks)
  EXPECT_EQ(l.estimated.size(), 3u);
  for (const char* name : {"pronasale", "nasion", "glabella"})
    EXPECT_NE(std::find(l.estimated.begin(), l.estimated.end(), name), l.estimated.end()) << name;
  // Estimated in order up the cut, inside the skin's z range.
  EXPECT_LT(l.points.at("stomion").z(), l.points.at("subnasale").z());
  EXPECT_LT(l.points.at("subnasale").z(), l.points.at("pronasale").z());
  EXPECT_LT(l.points.at("pronasale").z(), l.points.at("nasion").z());
  EXPECT_LT(l.points.at("nasion").z(), l.points.at("glabella").z());
  EXPECT_LE(l.points.at("glabella").z(), patient.V.col(2).maxCoeff());
}

}  // namespace
}  // namespace facehex
