#pragma once
// The mid-sagittal plane's trace from the head levels' mirror centres (rule 2 of core/segment/face_anatomy.h).
//
// A level's centre c is where its front is most mirror-symmetric. On most levels that is the face's plane; on some the
// front is no face and its centre can lie anywhere in the searched range, as often on one side as on both: a nose cut
// flat by the field of view (a plateau is symmetric about any point of it), the neck's folds, a lip or cheek bulging
// on one side, a support or collar. A least-squares line through all levels is dragged towards those, and so is one
// refitted without the levels far off it when they outnumber the face's near it. The trace is instead found in two
// steps:
//  - the line most levels agree with: among the lines through each pair of levels and the vertical line through
//    each level's c, those leaning at most max_slope (dc/dz), the one with the most levels within `agreement` mm of
//    it (among equals, the one whose agreeing levels lie closest to it: the smallest sum of squared distances);
//  - the face's levels are those within twice `agreement` of that line (a face's levels wander by a few mm, the
//    nose's to one side of the forehead's, more than any one line through two of them shows); the trace is the least
//    squares line through them, fitted again through those of them within `agreement` of it (when three or more).
#include <vector>

namespace facehex {

struct LevelCentre {
  double z = 0, c = 0;  // mm: the level's height and its mirror centre's x
};

// c(z) = c0 + slope (z - z0), z0 the agreeing levels' mean height.
struct SymmetryTrace {
  double z0 = 0, c0 = 0, slope = 0;
  std::vector<int> agreeing;  // indices of the levels the trace was last fitted through, ascending

  double at(double z) const { return c0 + slope * (z - z0); }
};

// At least one level. O(n^3) in the levels' count, which is a head's height in 2 mm steps.
SymmetryTrace consensus_trace(const std::vector<LevelCentre>& levels, double agreement, double max_slope);

}  // namespace facehex
