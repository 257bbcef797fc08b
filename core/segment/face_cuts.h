#pragma once
// The cut planes that bound the facial soft-tissue model, and where they go when not given.
//
// In the head frame (core/mesh/head_turn.h: the segmentation frame, +y anterior and +z superior, turned about the
// vertical axis and pitched about the lateral one so that a turned or pitched head's face looks to +y, upright; the
// segmentation frame itself when the head is neither):
//   top cut      z = top_z + top_slope (x - centre_x)  (side v1): just above the eyebrows, or the top of the CT when
//                that is lower; level but on a head tilted towards a shoulder;
//   bottom cut   z = bottom_z + bottom_slope (x - centre_x)  (side v0): below the chin; level but on a head tilted
//                towards a shoulder;
//   posterior    y = posterior_y + posterior_slope (x - centre_x)  (sides u0 at x < centre_x, u1 at x > centre_x): in
//                front of the ears, vertical; posterior_y is where it crosses the mid-sagittal plane;
//   jaw cut      y - (posterior_slope + bottom_slope) (x - centre_x) + z = posterior_y + jaw_z (side v0 too), rising
//                backwards at 45 degrees from the bottom cut to z = jaw_z on the posterior cut. Under the jaw the soft
//                tissue runs back to the neck, so the posterior cut alone would cut it right across, joining u0 and u1
//                under the chin; the jaw cut takes away the back of the submental region so that the posterior cut
//                meets two separate lateral pieces, as in the standard mesh (whose lower boundary also rises from the
//                chin back towards the ears).
// Automatic placement from the anatomy (face_anatomy.h, which states how each landmark is found); each value can be
// given instead:
//   centre_x    = the mid-sagittal plane at the pronasale's level, from the face's mirror symmetry;
//   bottom_z    = the menton (lowest point of the bony chin) minus chin_clearance, but at least border_margin above
//                 the CT's bottom and above its lowest slice with any body in it (a scan that starts within the
//                 chin: a cut below the body would leave the model no bottom side); where the mid-sagittal plane the
//                 landmarks are read on leans (landmark_plane: a head tilted towards a shoulder), the cut is
//                 perpendicular to it, chin_clearance under the menton (bottom_slope = -dx/dz of the plane), so that
//                 the shoulder the tilt raises on one side stays out of the model, unless that cut would leave the
//                 scan under the head's section at the menton's level (it stays level then);
//   top_z       = the glabella plus brow_clearance (above the eyebrows; the glabella read on the skin under an object
//                 lying on the brow when the segmentation found one there, FaceCutOptions::glabella), but at least
//                 border_margin below the CT's top, below the head's highest level (a scan that ends within the
//                 forehead) and below the highest level at which the forehead's front is whole (face_anatomy.h rule 3b:
//                 a scan whose last slice leans across the forehead) and the face region's section is (section_end_z:
//                 going up from the nasion, the head voxels in front of the posterior cut lose less than kScanEndSlope
//                 mm of mean depth per mm of height; a last slice leaning across the region, down to the back or to the
//                 front, takes a wedge from it level by level); the lowest of those less border_margin when the profile
//                 shows no brow (FaceAnatomy::brow_unseen); where the landmarks' plane leans, the cut through glabella
//                 + brow_clearance is perpendicular to it (top_slope = bottom's) unless so tilted it would rise above
//                 the lowest of those bounds over the head's section at the glabella's level (it stays level then);
//   posterior_y = the line in front of the ears (ears_line: through the tragi, core/segment/tragus.h) moved
//                 ear_clearance forward, each side the same distance in front of its own ear (a face's asymmetry, or
//                 what is left of a turn of the head, moves them apart);
//                 where the scan ends across the side or the back of the head from the mouth's level (half way from
//                 the menton to the pronasale) to the top cut's (core/segment/field_of_view.h) in front of that cut,
//                 or, wherever it ends there, when the ears' cut lies less than kMinFaceDepth behind the pronasale (a
//                 cheek's bulge, or the rows where the head is widest because the scan ends there, read as ears):
//                 coronal, border_margin in front of where it ends; a face region then less than kMinFaceDepth deep
//                 is refused (the scan holds too little of the face for the standard's);
//   jaw_z       = just above the highest model voxel on the posterior cut within one voxel of the mid-plane, in the
//                 lower half of the face (find_jaw_cut, once the soft tissue is known); none if there is none.
#include <limits>
#include <optional>
#include <vector>

#include "core/mesh/mid_sagittal_plane.h"
#include "core/mesh/sides.h"
#include "core/segment/face_anatomy.h"
#include "core/segment/field_of_view.h"
#include "core/segment/voxel_grid.h"

namespace facehex {

struct FaceCutOptions {
  std::optional<double> top_z, bottom_z, posterior_y, centre_x;  // mm, head frame
  // Degrees the head is turned about the vertical axis (core/mesh/head_turn.h; 0: the CT's own frame); found from the
  // head's symmetry when unset (find_head_turn), and a turn under kMinHeadTurn is taken as none.
  std::optional<double> head_turn;
  // Degrees the head is pitched about the lateral axis (core/mesh/head_turn.h; positive: the chin raised); none when
  // unset.
  std::optional<double> head_pitch;
  // The glabella (head frame) the top cut is placed by instead of the profile's (face_anatomy.h rule 3): the one read
  // on the skin under an object lying on it (skin_objects.h), where the profile takes the object's front for the brow.
  std::optional<Eigen::Vector3d> glabella;
  double brow_clearance = 15.0;  // mm above the glabella (the eyebrows lie within it)
  double chin_clearance = 15.0;  // mm below the menton (the chin's soft tissue is about 10 mm thick there)
  double ear_clearance = 9.0;    // mm in front of the front of the ears (front_of_the_ears)
  double border_margin = 3.0;    // mm: top and bottom cuts stay this far inside the CT and inside the body
};

// A cut half-space boundary: points p with normal . p > offset are cut away (normal points out of the model).
struct CutPlane {
  Eigen::Vector3d normal;
  double offset = 0;
  Side side = V0;  // the posterior plane says U0: it is u0 at x < centre_x and u1 beyond
  double distance(const Eigen::Vector3d& p) const { return normal.dot(p) - offset; }
};

// A head turned less than this is segmented in the CT's own frame: its face's profile on the CT's sagittal plane is
// as good, and the turn found on an upright head is within it.
constexpr double kMinHeadTurn = 2.0;  // degrees

// A head whose hard palate slopes less than this (core/segment/palate_pitch.h) is not segmented again pitched back when
// its face or landmarks are not found in the CT's frame: the palate's slope varies by a few degrees from head to head,
// and the anatomy rules read faces pitched that little.
constexpr double kMinHeadPitch = 5.0;  // degrees

struct FaceCuts {
  HeadTurn turn;  // the head frame the cuts are planes of
  // Degrees the hard palate slopes towards the front in the CT's frame, positive up (core/segment/palate_pitch.h):
  // how far the head is pitched; none where no palate was found.
  std::optional<double> palate_pitch;
  double top_z = 0, bottom_z = 0, posterior_y = 0, centre_x = 0;
  double posterior_slope = 0;  // dy/dx of the posterior cut: 0 for a coronal one
  // dz/dx of the top cut, and of the bottom cut and the jaw cut's rise: 0 for level ones (find_face_cuts: a head
  // tilted towards a shoulder has them perpendicular to its leaning mid-sagittal plane).
  double top_slope = 0, bottom_slope = 0;
  double jaw_z = -std::numeric_limits<double>::infinity();  // -infinity: no jaw cut
  // y of the most anterior place the scan ends across the side or the back of the head at the face's levels
  // (posterior_y above; field_of_view.h), where it does; whether the automatic posterior cut was placed by it.
  std::optional<double> scan_edge_y;
  bool scan_edge_at_disc = false;  // that place is on the edge of the CT's reconstruction disc, not of its box
  bool posterior_at_scan_edge = false;
  // The highest level at which the face region's section is whole (top_z above); +infinity up to the grid's top.
  double section_end_z = std::numeric_limits<double>::infinity();
  std::optional<FaceAnatomy> anatomy;  // what the automatic cuts were placed by; empty if all given

  std::vector<CutPlane> planes() const;
  // y of the posterior cut at x.
  double posterior_y_at(double x) const { return posterior_y + posterior_slope * (x - centre_x); }
  // z of the top and the bottom cut at x (top_z and bottom_z at the mid-plane).
  double top_z_at(double x) const { return top_z + top_slope * (x - centre_x); }
  double bottom_z_at(double x) const { return bottom_z + bottom_slope * (x - centre_x); }
  // Degrees the posterior cut turns from the head frame's x axis, towards +y at +x.
  double posterior_turn_degrees() const;
};

// Where the scan's first and last slices lie (mm, the CT's frame) and the head frame of the grids below: a pitched
// head's scan ends in planes tilted in its head frame, and the automatic top cut stays below the last over the face's
// depth (from the posterior cut to the pronasale), the bottom cut above the first at the chin (the menton's depth),
// rather than within the grid's own first and last levels.
struct ScanSlab {
  double z_lo = 0, z_hi = 0;
  HeadTurn turn;
};

// The front of the ears: the more anterior tragus found (face anatomy rule 6), else where it would lie, 3 mm in front
// of the auricles' front edge (rule 5). The tragus moves less with the auricle's outline than the auricle's front edge
// does.
double front_of_the_ears(const FaceAnatomy& anatomy);

// The vertical plane y = y_at_centre + slope (x - centre_x) in front of which the posterior cut keeps its clearance
// from the ears: through the two tragi found; with one tragus found, through it and, on the other side, the point at
// its mirror image's x 3 mm in front of that side's auricle edge (rule 5, where an auricle stands out); coronal
// through front_of_the_ears otherwise, or when the line turns more than kMaxPosteriorCutTurn.
struct EarsLine {
  double y_at_centre = 0, slope = 0;
};
EarsLine ears_line(const FaceAnatomy& anatomy, double centre_x);

// The face region reaches at least this far behind the nose tip (the pronasale): the standard's reaches back to in
// front of the ears, about 90 to 110 mm; a scan that ends across the cheeks nearer the face than this holds too
// little of it to map the standard onto.
constexpr double kMinFaceDepth = 65.0;  // mm

// The line through the two tragi found turning more than this from the head frame's x axis is not taken for the
// posterior cut's direction (a tragus read on a helix or a scar), which is then coronal. A head turned in the scanner
// is turned back by the head frame (FaceCutOptions::head_turn), so what is left is the ears' own asymmetry and the
// error of the turn.
constexpr double kMaxPosteriorCutTurn = 12.0;  // degrees

// `head` is the body (with its ears), `without_ears` the body opened (find_face_anatomy), `bone` the bone voxels, on
// the same grid; `slab`: where the scan ends, when the grid is pitched (else the grid's first and last levels).
// The anatomy is looked for unless all four values are given. Throws facehex::Error("segment", ...) if it cannot be
// found (naming the option that places the cut by hand) or if the cuts leave no face (bottom above top, ...).
// scan_edge: where the scan ends across the head (field_of_view_contacts, head frame), or none.
FaceCuts find_face_cuts(const Mask& head, const Mask& without_ears, const Mask& bone, const FaceCutOptions& options,
                        const std::optional<ScanSlab>& slab = std::nullopt,
                        const std::vector<FieldOfViewContact>& scan_edge = {});

// The mid-sagittal plane the landmarks are read on (core/mesh/mid_sagittal_plane.h), stored with the model: the cuts'
// plane, leaning as the head does when the symmetry's fit leans more than kLandmarkPlaneMinLean and the line between
// the two tragi, where both were found, leans within kLandmarkPlaneLeanAgreement of it, or, without the two tragi,
// when at least kLandmarkPlaneLeanSupport of the head levels agree with the fit (FaceAnatomy::roll_support) or the
// head's 3D mirror plane leans within kLandmarkPlaneLeanAgreement of it (FaceAnatomy::mirror_roll_degrees); else
// vertical through centre_x (as a plane given with --mid-plane is). On upright heads the fit leans by a few degrees
// through the neck and skull, and the face's profile is read better on the vertical (docs/benchmarks.md); an uneven
// shape (a warp's bumps, a clipped face) can lean the fit further on a head the level tragi show upright, and where
// half the levels' mirror centres wander (a coarse scan's chin and mouth) a fit that leans has no more levels behind
// it than the vertical has.
constexpr double kLandmarkPlaneMinLean = 5.0;        // degrees
constexpr double kLandmarkPlaneLeanAgreement = 5.0;  // degrees
constexpr double kLandmarkPlaneLeanSupport = 2.0 / 3.0;
MidSagittalPlane landmark_plane(const FaceCuts& cuts, const FaceCutOptions& given);

// Sets cuts.jaw_z from the model mask (before the cuts are applied): `clearance` mm above the highest model voxel in
// the posterior plane's voxel row that lies within one voxel of the mid-plane x = centre_x.
void find_jaw_cut(const Mask& model, double clearance, FaceCuts& cuts);

}  // namespace facehex
