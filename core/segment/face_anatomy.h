#pragma once
// The anatomy the face cuts are placed by, read from the head and bone masks of a CT (segmentation frame: +x lateral,
// +y anterior, +z superior), whatever else the scan holds (shoulders, a support, the whole skull).
//
// Rules, in the order they are applied:
//  1. head levels: the slices above the highest one in the lower half of the head that is more than kShoulderWidth
//     times as wide as the median width of the upper half: those are shoulders (or a support); the symmetry and the
//     pronasale are looked for above them (the chin may reach down among them);
//  2. mid-sagittal plane from the face's mirror symmetry: per head level, the front of the head d(x) (most anterior
//     head voxel of each column) is compared with its mirror image about x = c, up to a linear term a s (a head
//     turned about the vertical axis makes the front a little deeper on one side, proportionally to the distance s
//     from the plane); c minimises the mean squared difference within kSymmetryReach of the plane (among equals, the
//     nearest to the head's mean x). The plane's trace is the straight line c(z) fitted through the face's levels,
//     those near the line the most levels' c agree with (core/segment/symmetry_trace.h: a clipped nose, the neck or a
//     one-sided bulge can put many levels' c far to one side); its slope is the head's roll (tilt towards a shoulder),
//     refused beyond kMaxRoll (25 degrees: no head lies so in a scanner, and a fit that leans more has read the
//     symmetry wrongly, as on a head turned far about the vertical axis). A level of a tilted head cuts its two sides
//     at different heights, so where the trace leans more than 5 degrees each level's c is measured again on the row
//     across the leaning plane (perpendicular to the trace, within 10 mm of it) and the trace fitted again, until its
//     lean settles; the passes start from the level trace and from the head's 3D mirror plane (rule 0), when each
//     leans so. The pass most levels agree with is taken when two thirds of them do, else the best pass from the 3D
//     plane (the head's symmetry as a whole decides where its levels, cut by the field of view, do not), else the
//     level trace. A turned head keeps its plane through the nose, at the depth of the face's features;
//  3. the skin profile: per head level, the most anterior head voxel within kProfileBand of c(z);
//     pronasale = the most anterior profile point at the levels of the nasal aperture (the highest run, at least
//     kApertureHeight tall, of levels where the bone within the profile band lies more than kChinSoftTissue behind the
//     skin or is absent, with bone near the skin right above and below it; the whole profile when there is no such
//     run), the middle of the front plateau when the field of view cut the nose flat (such a cut can leave the forehead
//     as far forward as the nose); nasion = the least anterior profile point 15-50 mm above it that has a point at
//     least as anterior 3-30 mm above it (a hollow below the brow, not the head's top receding where the scan ends);
//     glabella = the most anterior profile point 3-30 mm above the nasion (middles of ties within half a voxel). When
//     no point has a brow above it (the scan ends below the brow, or a field-of-view cut flattens the face),
//     brow_unseen: the glabella is the most anterior point from the pronasale up and the top cut is the head's top
//     (face_cuts.h);
//  3b. the forehead's end: going up from the nasion (15 mm above the pronasale when the brow is unseen), in each
//     column within kForeheadHalfWidth of the plane, the first level that is empty or whose front lies further behind
//     the front a few mm below it (kScanEndRise, two slices at least) than kScanEndSlope times that rise: a
//     forehead recedes less steeply, and what does is where the scan ends across the forehead with its slices tilted
//     against the head (a head pitched in the scanner, slices resampled from a tilted gantry) or, far above, the
//     head's vertex. That column's front is whole up to the last level within a voxel of the front below the rise;
//     forehead_end_z is the lowest level a quarter of the columns end at (one or two columns at a strap's or a hair
//     clip's corner do not decide), and the top cut stays below it (face_cuts.h);
//  4. the bony chin: going down from 30 mm below the pronasale (below the head levels too), the levels where bone near
//     the mid-plane (within kChinHalfWidth) lies at most kChinSoftTissue behind the skin profile, joined into runs
//     over gaps of at most kChinGap; the chin's run is the tallest (the upper teeth and alveolar bone make a shorter
//     one above it when the lips are further apart); menton = the lowest bone voxel connected, within the mid-plane
//     band and going down and at most kChinDepth backwards, to the bone at that run's lowest level (the lower border
//     of the mandible curves back, under the skin's horizontal reach), of that level's such voxels the one nearest
//     the plane, then the most anterior. A nose tip less than 30 mm or more than 115 mm above the menton is no face's
//     (adults' lie within about 60 to 100 mm): not a plausible head, as where no nose stands out;
//  5. the ears: the auricle is thin, so the opening of the body (soft_tissue.h, opening_radius) removes it; per side,
//     over the levels from 25 mm below the pronasale to the glabella and in the middle half of the head's depth
//     there, a coronal row holds the ear where the body reaches at least kEarStandOut further sideways than the body
//     without its ears, on levels at least kEarMinHeight tall in all; an ear's front is the most anterior such row
//     (the auricle's front edge, beside the tragus), and the ears' front is the more anterior of the two (a turned
//     head has one ear further forward). The front of the auricle, rather than where the head is widest, since how
//     far back the helix flares out varies from head to head and moves the widest row by centimetres. Where no
//     auricle stands out (the field of view cuts the ears off, or a support presses them flat), ears_estimated: an
//     ear's front is the most anterior row whose reach from the plane on that side is within kEarReachTolerance of
//     the furthest;
//  6. the tragi: core/segment/tragus.h.
#include <Eigen/Core>
#include <array>
#include <limits>
#include <string>

#include "core/mesh/ct_landmarks.h"
#include "core/mesh/head_turn.h"
#include "core/segment/voxel_grid.h"

namespace facehex {

// A front, or a section's mean depth, that recedes more steeply than this over a rise of kScanEndRise (two slices at
// least, since a slice's front moves by whole voxels) is where a scan ends across the head, not anatomy: a forehead
// recedes at about 1 mm per mm at most below the head's vertex, and a scan end tilted by less than about 18 degrees
// against the head takes away more than 3.
constexpr double kScanEndSlope = 3.0;  // mm per mm of height
constexpr double kScanEndRise = 3.0;   // mm

struct FaceAnatomy {
  double centre_x = 0;      // mid-sagittal plane at the pronasale's level
  double roll_degrees = 0;  // the plane's trace leans by this angle from vertical (positive: +x upwards)
  double roll_support = 1;  // the fraction of the head levels the trace was fitted through (rule 2)
  // The head's 3D mirror plane's roll (rule 2), NaN where it leans 5 degrees or less.
  double mirror_roll_degrees = std::numeric_limits<double>::quiet_NaN();
  Eigen::Vector3d pronasale, nasion, glabella;  // skin points of the mid-sagittal profile
  bool nose_clipped = false;                    // the front of the nose is a plateau (field-of-view cut)
  bool brow_unseen = false;                     // no nasion below a brow in the profile (rule 3); nasion = pronasale
  Eigen::Vector3d menton;                       // bone: the lowest point of the chin
  double ear_front_y = 0;                       // y of the front of the ears (the auricles' front edges), rule 5
  bool ears_estimated = false;                  // no auricle stands out: the front of the widest rows (rule 5)
  // Each ear's front (-x side, +x side); -inf: not seen.
  std::array<double, 2> ear_fronts_y = {-std::numeric_limits<double>::infinity(),
                                        -std::numeric_limits<double>::infinity()};
  Tragi tragi;                // rule 6: right (-x) and left (+x), none where not seen
  double lowest_head_z = 0;   // below this the slices are shoulders or a support
  double highest_head_z = 0;  // the highest level of the head in the scan
  // Rule 3b: the highest level at which the forehead's front is whole; +infinity if it is up to the head's top.
  double forehead_end_z = std::numeric_limits<double>::infinity();
  // The glabella was read on the skin under an object lying on the brow (FaceCutOptions::glabella), not on the profile.
  bool glabella_under_object = false;

  // The mid-sagittal plane's x at height z.
  double centre_at(double z) const;
  double roll_slope = 0, roll_z = 0;  // c(z) = centre_x + roll_slope (z - roll_z)
};

// Rule 0, before the others (they read the head in its head frame, core/mesh/head_turn.h): the head's turn about the
// vertical axis is the angle t within +-kMaxTurn (40 degrees) at which the head's horizontal sections above the
// shoulders (rule 1) are the most mirror-symmetric about the line through each one's centroid along (sin t, cos t):
// the largest fraction of head voxels (sampled every 2 mm) whose mirror image is a head voxel too; searched every
// degree, then every 0.1 degree around the best. The axis is the vertical line through the sections' centroid. A head
// tilted towards a shoulder cuts each section's two sides at different heights, which turns the sections' mirror
// lines: where the head's mirror plane in 3D (the turn and the roll at which the most head voxels of those levels,
// sampled every 4 mm, mirror into the head, the plane within 6 mm of their centroid) leans more than 5 degrees, its
// turn is taken.
HeadTurn find_head_turn(const Mask& head);

// `head` is the body with its ears, `without_ears` the same opened (the ears removed), `bone` the bone voxels, on one
// grid. Throws facehex::Error("segment", ...) naming what cannot be found and the cut options that place it by hand,
// or saying that the volume is not a plausible head when no nose stands out of its profile.
FaceAnatomy find_face_anatomy(const Mask& head, const Mask& without_ears, const Mask& bone);

// Throws facehex::Error("segment", "not a plausible head: ...") unless the head (or body) is wide and deep enough for
// one (a small phantom or a CT of a few voxels is not).
void check_head_size(const Mask& head);

// "pronasale (x, y, z), ..." on one line, mm.
std::string face_anatomy_text(const FaceAnatomy& anatomy);

}  // namespace facehex
