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
// A field-of-view cut: when the front of the profile is a plateau (within 3.5 mm of its most anterior point) at least
// 25 mm long, the scan cut the face flat there (a nose drops more than that within 25 mm of its tip). Then the upper
// lip, subnasale, stomion and lower lip are found below the cut, and the pronasale, nasion and glabella inside it
// are placed by typical adult proportions above the subnasale (15, 55 and 67 mm), listed in `estimated`.
// Each feature constraint pins the chosen field on the skin (and on walls of openings, e.g. the standard's mouth
// slit) near the landmark: v on the horizontal plane through it, u = 0.5 on the mid-sagittal plane (whole volume).
#include <Eigen/Core>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "core/fields/constraint_set.h"
#include "core/mesh/mesh.h"

namespace facehex {

struct FaceLandmarks {
  double x_mid = 0;
  std::map<std::string, Eigen::Vector3d> points;  // "pronasale", "subnasale", "nasion", "glabella", "stomion", ...
  // Where the profile is clipped flat by the scan's field of view (z range, mm; NaN if it is not), and the landmarks
  // that lie inside the cut and were placed by typical proportions instead of found.
  double clipped_from = std::numeric_limits<double>::quiet_NaN(), clipped_to = clipped_from;
  std::vector<std::string> estimated;
};

struct LandmarkOptions {
  double profile_band = 3.0;     // mm
  double clipped_depth = 3.5;    // mm: profile points this close to the most anterior one are on a front plateau
  double clipped_length = 25.0;  // mm: a front plateau this long is a field-of-view cut, not anatomy
};

// V #V x 3, side_mask #V. Throws facehex::Error("landmarks", ...) naming the landmark that cannot be found.
FaceLandmarks find_face_landmarks(const Eigen::MatrixXd& V, const Eigen::VectorXi& side_mask,
                                  const LandmarkOptions& options = {});

// One line per landmark, "name at (x, y, z) mm", marked "(estimated)" where placed by proportions, and a first line
// naming the field-of-view cut if there is one; each line starts with `indent`.
std::string landmarks_text(const FaceLandmarks& landmarks, const std::string& indent);

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
