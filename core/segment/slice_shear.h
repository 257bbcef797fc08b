#pragma once
// Slices stacked with in-plane offsets, resampled onto one upright grid.
//
// A CT acquired with its gantry tilted (to spare the eyes' lenses, or along the orbitomeatal line) is reconstructed in
// slices whose planes are the scanner's axial planes but whose origins move along the columns from slice to slice: the
// volume they stack into is sheared, a head in it leans by the tilt. DICOM says so only through the slices' positions
// (ImagePositionPatient moving in plane as well as along the normal), which 3D Slicer and ITK read the same way.
#include <Eigen/Core>
#include <vector>

#include "core/segment/voxel_grid.h"

namespace facehex {

// `stacked`: the slices as read, slice k at grid level k, its in-plane origin at stacked's origin plus offsets[k]
// (mm, along the grid's x and y; #offsets = the number of slices). Returns the volume on an upright grid that holds
// every slice: its x and y extent the union of the slices' (the first slice's spacing), each voxel the bilinear
// interpolation of its slice at its position, `fill` where the slice does not reach. Offsets that are whole multiples
// of the spacing give the slices' values exactly.
Field unshear_slices(const Field& stacked, const std::vector<Eigen::Vector2d>& offsets, float fill);

}  // namespace facehex
