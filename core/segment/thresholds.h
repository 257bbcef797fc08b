#pragma once
// Skin and bone intensity thresholds of a CT, found from its intensity histogram.
//
// A head CT's histogram has a large air mode, a soft-tissue mode and a long bone tail (voxels at the volume's lowest
// value are left out when the rest still has an air mode: a scanner's fill outside its field of view):
//   - Otsu's threshold splits air from everything denser;
//   - the air mode and the soft-tissue mode are the highest (smoothed) peaks on either side of it;
//   - skin  = half way between the two modes: where a blurred air-tissue edge crosses its middle, so the skin lies
//             where the edge is whatever the blur (the valley between the modes is broad and flat on a coarse CT, and
//             its deepest point wanders with noise and resampling);
//   - bone  = the first intensity above the soft-tissue mode where the (smoothed) histogram has fallen below
//             kBoneTailFraction of the mode's height, i.e. where soft tissue (plus its noise) ends. On a CT blurred
//             to remove its noise (ct_noise.h) the blur spreads the bone's edges into the valley above the soft
//             tissue, and the histogram no longer falls that low where the soft tissue ends: there the bone threshold
//             is where a Gaussian peak of the soft-tissue mode's upper half-width falls to kBoneTailFraction, which
//             the bone's edges, below half the peak's height, do not move (BoneThresholdRule::peak_width).
// On calibrated CTs this gives about -500 HU / +150 HU (bone this low still stops the soft tissue at the bone
// surface; pass thresholds explicitly to be stricter).
#include "core/segment/voxel_grid.h"

namespace facehex {

struct TissueThresholds {
  double skin = 0;  // intensity >= skin: body (soft tissue or denser)
  double bone = 0;  // intensity >= bone: bone
};

constexpr double kBoneTailFraction = 0.05;

enum class BoneThresholdRule { histogram_tail, peak_width };

// The histogram's air and soft-tissue modes, file units (the skin threshold is their midpoint).
struct IntensityModes {
  double air = 0, tissue = 0;
};

// Throws facehex::Error("thresholds", ...) when the histogram has no air/soft-tissue structure (e.g. a constant
// volume). `modes`, when given, gets the modes the thresholds lie between.
TissueThresholds estimate_thresholds(const Field& intensity, BoneThresholdRule rule = BoneThresholdRule::histogram_tail,
                                     IntensityModes* modes = nullptr);

}  // namespace facehex
