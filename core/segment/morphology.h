#pragma once
// Binary morphology with Euclidean balls (radius in millimetres), built on the exact distance transform, and
// connected components (6-connected: face neighbours).
#include <vector>

#include "core/segment/voxel_grid.h"

namespace facehex {

Mask dilate(const Mask& mask, double radius);
Mask erode(const Mask& mask, double radius);  // voxels beyond the grid count as outside
// Dilation then erosion, on a grid padded by replicating its border slices so that the mask is not eroded where it
// is cut by the grid (the top and bottom slices of a head CT).
Mask close(const Mask& mask, double radius);
// Erosion, the largest piece of what is left, dilation, within the mask: removes parts thinner than 2 * radius and
// whatever they alone attached.
Mask open(const Mask& mask, double radius);

// 6-connected components of the nonzero voxels: labels 1..n per voxel (0 = not in the mask), sizes[l] = voxel count
// of component l (sizes[0] = 0). Returns n.
int label_components(const Mask& mask, std::vector<int>& labels, std::vector<size_t>& sizes);
Mask largest_component(const Mask& mask);

// Fills every 6-connected region of zero voxels that does not touch one of the "open" grid faces, given per face in
// the order -x, +x, -y, +y, -z, +z. With the x and y faces open only, the trachea leaving through the bottom slice
// still counts as enclosed.
Mask fill_cavities(const Mask& mask, const std::array<bool, 6>& open);

}  // namespace facehex
