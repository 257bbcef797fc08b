#pragma once
// The eye corners (endocanthion and exocanthion, right and left) read from the CT's own grey values. A closed eye's
// slit is a notch in the skin one or two millimetres tall and a few deep; the segmentation's smoothed skin bridges
// it, so the corners are read from the CT, where the notch is kept.
//
// In the head frame of the face's mid-sagittal plane (core/mesh/head_turn.h, +x the side named left, +y anterior, +z
// superior), with x = c the plane at the nasion's height and "offset" the distance |x - c|, each side on its own; on a
// head tilted towards a shoulder (the plane leaning), the levels below are heights above the line through the nasion
// across the plane (perpendicular to its trace), along which a tilted face's eye line runs:
//  1. the front of the face (face_front.h), the rays cast from kRayFront in front of the pronasale, over
//     kFieldHalfWidth either side of the plane and the levels from kBelow below to kAbove above the nasion (and
//     kFieldMargin more);
//  2. the notch depth of a point: how far y lies behind the chord between the points kChord above and below it,
//     averaged over the columns 1 mm either side. The slit's line: from the level of deepest mean notch over the
//     columns kSeedInner-kSeedOuter out, kSeedLowest to 0 mm below the nasion, the deepest notch followed column by
//     column (1 mm steps, moving at most 1 mm in z per column) outwards to kOuter and inwards to kInner;
//  3. the slit is seen when the narrow notch (chord kNarrowChord, the slit's own height) along the outer line, in a
//     running mean of 3 columns, is at least kMinSlitDepth deep somewhere kExoInner-kExoOuter out;
//  4. exocanthion: the first point, outwards from kExoInner (up to kExoOuter), where the slit's floor (the rearmost y
//     within kFloorBand of the line's height), measured from the lids' skin around it (the front's mean kLidsNear to
//     kLidsFar above and below the line), has a local minimum whose pit ends in a rise: the pit's bottom is the deepest
//     point within kPitReach, moved out while the next point lies within kBottomTolerance of it, and the floor rises by
//     kPitRise within kPitReach beyond the minimum or beyond that bottom (a slit growing shallower outwards has its
//     last minimum further in than kPitReach from the step where it ends). The slit ends at the pit's bottom and the
//     lids' outer fold begins. Measured from the lids, the floor's rise is not hidden where the face itself recedes
//     steeply (a temple turned away from the front);
//  5. endocanthion: going inwards along the line, the last column before the line climbs the nose's side (its y rising
//     more than 1 mm per mm) or leaves the slit: its height moves by kReach or more between neighbouring columns, the
//     most the line may move, so that it follows no notch of its own (smooth skin) or has taken another one (the lid's
//     fold above the inner corner); none where that column lies further out than kMaxEndoFraction of the
//     exocanthion's offset (no adult's inner corner does: the line lost the slit, as between thick slices), and the
//     estimate of rule 7 then lies at the slit's height there;
//  6. the height of a found corner: the middle of the slit's floor in its column (the samples within kFloorTolerance
//     of the rearmost y within kRefine of the line), unless that run reaches the window's end;
//  7. a corner not seen (no slit: open eyes seen as a hole, a notch too shallow for the scan's voxels, no seed) is
//     estimated by adult proportions: the exocanthion kEstimatedExoOffset out at the line's height (within the seed's
//     levels; kEstimatedExoDrop below the nasion when no line was followed), the endocanthion kEstimatedEndoFraction of
//     that out and kCanthalDrop lower, on the front.
// A corner whose column the rays do not reach (outside the scan) is none.
#include <Eigen/Core>

#include "core/mesh/ct_landmarks.h"
#include "core/mesh/mid_sagittal_plane.h"
#include "core/segment/voxel_grid.h"

namespace facehex {

// `ct` the CT's intensities in the model's frame, `skin_threshold` in its units; the face's mid-sagittal plane, nasion
// and pronasale in the model's frame (core/face/face_landmarks.h). The corners in the model's frame, in
// kEyeCornerNames order.
EyeCorners find_eye_corners(const Field& ct, double skin_threshold, const MidSagittalPlane& plane,
                            const Eigen::Vector3d& nasion, const Eigen::Vector3d& pronasale);

}  // namespace facehex
