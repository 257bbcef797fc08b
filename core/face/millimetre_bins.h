#pragma once
// The 1 mm bins the landmark finder sorts skin points into (the profile's heights, the front height field's cells).
#include <cmath>

namespace facehex {

// The bin of a coordinate t, in mm from the bins' origin. A point on a bin's edge, to within a micrometre, counts to
// the bin above however its coordinate was rounded: an iso-surface of a 1 mm grid puts many of its vertices on whole
// millimetres, and which bin a whole plane of them falls in must not depend on the last bit of a frame change.
inline int millimetre_bin(double t) {
  constexpr double kEdgeTolerance = 1e-3;  // mm
  return static_cast<int>(std::floor(t + kEdgeTolerance));
}

}  // namespace facehex
