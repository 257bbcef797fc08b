#pragma once
// A voxel volume (a CT) pushed through a smooth warp: the warped volume holds at W(x) what the original holds at x,
// so that segmenting it gives the original's anatomy moved by W.
#include "core/evaluation/smooth_warp.h"
#include "core/segment/voxel_grid.h"

namespace facehex {

// The warped volume on a grid of the original's spacing whose box holds the image of the original's box (W of its
// faces) across, and in z only the levels the image of the original covers across its whole area: a scanner's volume
// ends in slice planes, where W bends the original's end slices into curved ends. A pitched warp (pitch_degrees) keeps
// the whole image in z too: its tilted end slices would crop the face. Each voxel y takes the original's
// trilinear sample at W^-1(y) (voxel_grid.h sample), and where W^-1(y) lies outside the original's box (by more than
// half a voxel), the original's lowest value: nothing was scanned there, and a border value carried outwards would add
// tissue that the original does not have.
Field warp_volume(const Field& field, const SmoothWarp& warp);

// What a CT's random warps are drawn about (smooth_warp.h random_warp), from the volume alone, so that a seed gives
// the same warp whatever the segmentation and the transfer under test do: the anchors are the face-on skin, the most
// anterior (+y) voxel above the skin threshold (thresholds.h) of each column along y, within kWarpFrameDepth of the
// most anterior of them all; the centre is their mean.
constexpr double kWarpFrameDepth = 80;  // mm

struct CtWarpFrame {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::MatrixXd anchors;  // #A x 3, mm
};

// Throws facehex::Error("thresholds", ...) as estimate_thresholds does, or Error("benchmark", ...) when no voxel is
// above the skin threshold.
CtWarpFrame ct_warp_frame(const Field& intensity);

}  // namespace facehex
