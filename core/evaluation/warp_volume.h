#pragma once
// A voxel volume (a CT) pushed through a smooth warp: the warped volume holds at W(x) what the original holds at x,
// so that segmenting it gives the original's anatomy moved by W.
#include "core/evaluation/smooth_warp.h"
#include "core/segment/voxel_grid.h"

namespace facehex {

// The warped volume on a grid of the original's spacing whose box holds the image of the original's box (W of its
// faces) across, and in z only the levels the image of the original covers across its whole area: a scanner's volume
// ends in slice planes, where W bends the original's end slices into curved ends. Each voxel y takes the original's
// trilinear sample at W^-1(y) (voxel_grid.h sample), and where W^-1(y) lies outside the original's box (by more than
// half a voxel), the original's lowest value: nothing was scanned there, and a border value carried outwards would add
// tissue that the original does not have.
Field warp_volume(const Field& field, const SmoothWarp& warp);

}  // namespace facehex
