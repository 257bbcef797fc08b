#pragma once
// The stomion read from the CT's own grey values: closed lips meet in a slit a few millimetres deep that the
// segmentation's smoothed skin bridges, so the profile on that skin puts the stomion in front of the slit.
//
// In the head frame of the face's mid-sagittal plane (core/mesh/head_turn.h), the face's front (face_front.h) in the
// columns within kProfileHalfWidth of the plane, averaged into one profile y(z) every 0.25 mm from the labrale
// inferius up to the labrale superius; the stomion is its rearmost point, on the plane. None where that is the
// profile's first or last point (no slit between the lips), lies more than kMaxSlitDepth behind the less anterior
// lip (lips apart: the rays meet the teeth or enter the mouth), or where the profile has no front.
//
// Parted lips (an open mouth): the same profile's points that lie more than kMaxSlitDepth behind the less anterior lip,
// or whose rays meet nothing within 40 mm behind it (into the mouth), span the gap between the lips.
#include <Eigen/Core>
#include <optional>

#include "core/mesh/ct_landmarks.h"
#include "core/mesh/mid_sagittal_plane.h"
#include "core/segment/voxel_grid.h"

namespace facehex {

// `ct` the CT's intensities in the model's frame, `skin_threshold` in its units; the plane and the labralia as found
// on the model's skin (core/face/face_landmarks.h), in the model's frame. The stomion in the model's frame, found.
std::optional<CtLandmark> find_stomion(const Field& ct, double skin_threshold, const MidSagittalPlane& plane,
                                       const Eigen::Vector3d& labrale_superius,
                                       const Eigen::Vector3d& labrale_inferius);

// mm: how far apart the lips are at the midline, from the lowest to the highest of the profile's points that lie
// deeper than a closed slit (the header); 0 where the lips meet. Arguments as find_stomion's.
double parted_lips_gap(const Field& ct, double skin_threshold, const MidSagittalPlane& plane,
                       const Eigen::Vector3d& labrale_superius, const Eigen::Vector3d& labrale_inferius);

}  // namespace facehex
