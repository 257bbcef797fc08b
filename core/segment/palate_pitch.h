#pragma once
// How far a head is pitched (nodding) in the scanner, read from its hard palate: the bony plate between the nasal
// cavity and the mouth, which lies within a few degrees of the Frankfort horizontal in adults and deep in the face,
// away from what a field of view clips (a nose cut flat, a chin at the scan's edge) and from the neck and shoulders.
//
// On a sagittal band either side of the mid-sagittal plane (kBandInner to kBandOuter from it: beside the nasal
// septum, within the palate's width), two maps over (y, z): the fraction of the band's voxels that are bone, and
// "inside" (the band mostly head, filled front to back between the head's ends on each level, so that the nasal
// cavity and the mouth count as inside). A line of the (y, z) plane is a palate where, along it, there is a plate of
// bone (within a millimetre), nearly no bone from 4 to 15 mm below it (the tongue) and little from 4 to 8 mm above it
// (the nasal floor), and the head all around it within 20 mm (not the skull's vault, not where the scan ends); its
// length is the longest such run along it, over gaps of at most 4 mm, ending within 45 mm of the face's front (not a
// plate of the skull base). Lines at every 2 degrees from -50 to 50 and every millimetre of height are tried; along
// the longest run the plate's bone-weighted middle is taken every millimetre, and a line fitted through those points
// (weighted least squares, twice more without the points further off than 2.5 times the median residual, at least
// 1 mm) gives the angle.
//
// Frame: the segmentation's (head frame of a turned head, core/mesh/head_turn.h): +y anterior, +z superior. The angle
// is the palate's slope towards the front, degrees, positive with its front end up (the chin raised): the pitch
// that HeadTurn::pitch undoes. Measured on the bundled CT and the Visible Human pitched by known angles
// (docs/benchmarks.md, "A pitched head").
#include <optional>

#include "core/segment/voxel_grid.h"

namespace facehex {

inline constexpr double kBandInner = 3.0, kBandOuter = 10.0;  // mm from the mid-sagittal plane
inline constexpr double kMinPalateLength = 15.0;              // mm: a shorter run is no palate

// head: the head with its cavities filled; bone: bone voxels; on one grid of isotropic spacing. centre_x: the
// mid-sagittal plane's x. None when no run of kMinPalateLength or more is found.
std::optional<double> palate_pitch(const Mask& head, const Mask& bone, double centre_x);

}  // namespace facehex
