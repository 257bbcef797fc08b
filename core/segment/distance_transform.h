#pragma once
// Exact Euclidean distance transform on an anisotropic voxel grid (Felzenszwalb & Huttenlocher's separable lower
// envelope of parabolas), in millimetres, with the nearest feature voxel when asked.
#include <cstdint>
#include <vector>

#include "core/segment/voxel_grid.h"

namespace facehex {

// Distance from every voxel centre to the nearest voxel centre where `features` is nonzero (0 on those voxels,
// +infinity everywhere if there is none). Voxels beyond the grid are not features. If `nearest` is given, it gets
// the grid index of that nearest feature voxel (-1 where there is none).
Field distance_to(const Mask& features, std::vector<std::int64_t>* nearest = nullptr);

// The voxels where distance_to(features) <= radius (mm), the same ones, without its Field.
Mask within_distance(const Mask& features, double radius);

}  // namespace facehex
