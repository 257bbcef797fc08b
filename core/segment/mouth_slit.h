#pragma once
// The mouth corners (cheilion right and left) read from the CT's own grey values, where closed lips meet in a slit
// that the segmentation's smoothed skin bridges. Along the mouth line the slit is a notch a millimetre or two deep; at
// each corner it ends within a millimetre or two, where the lips' skin turns into the cheek's. That end is sharp in
// the CT and, measured against the slit's own depth, the same on a deeper or shallower face; on the model's skin
// (core/face/mouth_corners.h) the corner is a threshold crossing of the skin's steepness, which drifts along a mouth
// line whose steepness hovers about it.
//
// In the head frame of the face's mid-sagittal plane (core/mesh/head_turn.h, +x the side named left, +y anterior, +z
// superior), with x = c the plane at the stomion's height and "offset" the distance |x - c|, each side on its own; on
// a head tilted towards a shoulder (the plane leaning), the levels below are heights above the line through the
// stomion across the plane, along which a tilted face's mouth line runs:
//  1. the front of the face (face_front.h), the rays cast from kRayFront in front of the stomion over kHalfWidth
//     either side of the plane and kWindow above and below the stomion;
//  2. the notch depth at (offset, z): how far y lies behind the chord between the points kChord above and below it,
//     averaged over the columns within 1 mm (a column's noise averaged, a corner's end not);
//  3. the slit's line: from the stomion's level on the plane, column by column (kStep outwards), the deepest notch
//     within kReach in z of the previous column's, out to kHalfWidth or the front's end;
//  4. the slit's depth: the median notch on the line within kDepthNear of the plane. Lips not closed in a slit (a
//     depth below kMinDepth: lips apart, or a slit too narrow for the scan) have none;
//  5. the corner: the first point beyond kCornerNear where the line's notch, in a running mean over kMeanReach columns
//     either side, falls below kEndFraction of the slit's depth (linear between the two columns). None when it does
//     not by kCornerFar (beyond the widest adult mouth: the line left the slit) or the front ends first;
//  6. the corner's height: in its column, within kHeightBand of the line, where the front recedes fastest going down
//     (the largest dy/dz: the upper lip turning in over the slit); its y the front's there.
// None on a CT with voxels coarser than kMostSpacing in any axis: a slit a millimetre or two tall is then a voxel's
// partial volume, and its end not readable to a millimetre.
//
// Lips apart (an open mouth, stomion.h: parted_lips_gap) have no slit: their corners are where the gap between them
// ends. On the same front, over the labralia's heights and kOpenMargin beyond: in each column (the columns within 1 mm
// averaged), the gap's depth, how far the front lies behind the lower of the lips' fronts above and below it (a ray
// that meets nothing counts as reaching kRayBack); going out from the plane, the corner is the first point beyond
// kCornerNear where that depth, in the running mean of rule 5, falls below kOpenEndDepth (linear between the two
// columns), at the height of its column's deepest point, on the lips' front there. None where the depth is below
// kOpenEndDepth all the way out to kCornerNear (lips that meet), or as in rule 5.
#include <Eigen/Core>
#include <array>
#include <optional>

#include "core/mesh/ct_landmarks.h"
#include "core/mesh/mid_sagittal_plane.h"
#include "core/segment/voxel_grid.h"

namespace facehex {

// `ct` the CT's intensities in the model's frame, `skin_threshold` in its units; the face's mid-sagittal plane and the
// stomion read in the CT (stomion.h), in the model's frame. The corners in the model's frame, in kMouthCornerNames
// order (right, left), each found or none.
MouthCorners find_mouth_corners(const Field& ct, double skin_threshold, const MidSagittalPlane& plane,
                                const Eigen::Vector3d& stomion);

// An open mouth's corners (the header's last paragraph), by the labralia found on the model's skin.
MouthCorners find_open_mouth_corners(const Field& ct, double skin_threshold, const MidSagittalPlane& plane,
                                     const Eigen::Vector3d& labrale_superius, const Eigen::Vector3d& labrale_inferius);

}  // namespace facehex
