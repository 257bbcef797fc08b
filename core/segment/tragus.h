#pragma once
// Rule 6 of core/segment/face_anatomy.h: the tragi, read from the head mask (with its ears) in the segmentation
// frame (+x lateral, +y anterior, +z superior), each side on its own:
//  1. the side's reach map R(y, z): how far the row (y, z) of the head reaches sideways from the mid-sagittal plane
//     (0 where it does not reach past it), over the levels from kBelowBand below rule 5's band (the tragus can lie
//     below the auricle's rows) to the glabella, and the rows from kWindowBack behind that ear's front (rule 5) to
//     kWindowFront in front of it (the auricle's front edge can lie behind the tragus);
//  2. the ear's hollow (the concha and the ear canal's entry, seen from the side): where the grey closing of R by a
//     disc of kClosingRadius (wider than a concha's half) lies at least kMinDepth outside R. Its 4-connected pieces;
//     the hollow is the one with the largest sum of depths, with the pieces within kClosingRadius of it that are at
//     least kMinMaxDepth deep somewhere (a fold of the auricle splits a concha). None: a hollow whose depths sum to
//     less than kMinHollow (mm over its area in mm^2) or that is nowhere kMinMaxDepth deep;
//  3. per level, the hollow's front wall: going back from the hollow's front, the first row that lies in its deep
//     part (at least kDeepFraction of its greatest depth) with the skin reaching at least kWallHeight further out
//     within kWallGap in front of it. None: no level shows such a wall;
//  4. the tragus: the levels whose wall lies within kWallTolerance of the most anterior wall, contiguous from the
//     lowest level where it is the most anterior; its point is their mean height, the wall between the hollow's row
//     and the next in front, and the skin's reach in that next row: the lateral free edge of the tragus, where it
//     overhangs the hollow. None where that lies more than kMaxBehindAuricleEdge behind the auricle's front edge (a
//     wall inside the concha); estimated where rule 5 found no auricle standing out (its front of the widest rows).
#include "core/mesh/ct_landmarks.h"
#include "core/segment/face_anatomy.h"
#include "core/segment/voxel_grid.h"

namespace facehex {

// `head` is the body with its ears on the grid rule 5 read; the anatomy of rules 1-5. Right (-x) and left (+x); none
// on a side whose hollow or wall is not seen.
Tragi find_tragi(const Mask& head, const FaceAnatomy& anatomy);

}  // namespace facehex
