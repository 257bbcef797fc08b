#pragma once
// Facial landmarks from the skin surface of a model (standard or patient) and the feature constraints built on them
// (paper 3.4: mid-sagittal line, eyebrow line, below-nose line, middle lip line).
//
// Frame: +x lateral, +y anterior (the face looks to +y), +z superior. The skin is the model's w1 side (side_mask).
//  - mid-sagittal plane x = x_mid: first the middle of the skin's x range, then the x of the nose tip found near it;
//  - the profile: for 1 mm bins of z, the most anterior skin point within `profile_band` of the plane;
//  - pronasale (nose tip): the most anterior profile point in the middle 80 % of the z range;
//    subnasale: the least anterior point up to 25 mm below it; nasion: the least anterior point 10-45 mm above it;
//    glabella (brow ridge): the most anterior point up to 25 mm above the nasion;
//    labrale superius: the most anterior point up to 20 mm below the subnasale; labrale inferius: the most anterior
//    point 6-30 mm below that; stomion (lip contact): the least anterior point between the two.
// Each feature constraint pins the chosen field on the skin (and on walls of openings, e.g. the standard's mouth
// slit) near the landmark: v on the horizontal plane through it, u = 0.5 on the mid-sagittal plane (whole volume).
#include "core/constraint_set.h"
#include "core/mesh.h"

#include <Eigen/Core>
#include <map>
#include <string>

namespace facehex {

struct FaceLandmarks {
  double x_mid = 0;
  std::map<std::string, Eigen::Vector3d> points;  // "pronasale", "subnasale", "nasion", "glabella", "stomion", ...
};

struct LandmarkOptions {
  double profile_band = 3.0;  // mm
};

// V #V x 3, side_mask #V. Throws facehex::Error("landmarks", ...) naming the landmark that cannot be found.
FaceLandmarks find_face_landmarks(const Eigen::MatrixXd& V, const Eigen::VectorXi& side_mask,
                                  const LandmarkOptions& options = {});

// The names, fields and selection radii of the feature constraints.
struct FeatureSpec {
  std::string name, landmark;
  int field;
  double radius;  // mm around the landmark (0: the whole plane)
};
const std::vector<FeatureSpec>& feature_specs();

// Feature constraints at the landmarks with the given values per feature name (missing names: u = 0.5 for the
// mid-sagittal line; others are required). band: slab width in mm.
ConstraintSet feature_constraints(const FaceLandmarks& landmarks, const std::map<std::string, double>& values,
                                  double band);

}  // namespace facehex
