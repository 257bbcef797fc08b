#pragma once
// How noisy a CT is, and the blur that brings a noisy one (a low-dose CT, a cone-beam CT) down to a diagnostic CT's
// noise before it is segmented. The bone threshold is where the soft tissue's histogram peak ends (thresholds.h): noise
// widens that peak, the threshold rises above thin bone (the orbits' floors, the maxilla's walls), and the model then
// reaches through them into the sinuses with tunnels. Blurring first keeps the threshold and the masks a diagnostic CT
// would give; a CT already that quiet is left as it is.
#include "core/segment/thresholds.h"
#include "core/segment/voxel_grid.h"

namespace facehex {

// The voxel noise a diagnostic CT has, as a fraction of its air to soft-tissue contrast (about 25 HU).
constexpr double kDiagnosticNoise = 0.025;
// mm: the most the denoising blurs (beyond it the eyelids' and lips' slits close): a CT noisier than that is blurred
// this much and segmented, the summary saying how noisy it still is.
constexpr double kMostDenoisingBlur = 2.0;

struct CtNoise {
  double sigma = 0;     // file units: the standard deviation of the voxel noise in the soft tissue (0: not measured)
  double contrast = 0;  // file units: soft-tissue mode minus air mode of the histogram (thresholds.h)
  double blur = 0;      // mm: the Gaussian sigma that brings sigma down to kDiagnosticNoise * contrast (0: none needed)
  double sigma_after = 0;  // file units: what the blur leaves of sigma, were the noise white
};

// The noise of `intensity` from the differences of neighbouring voxels in x and in y (within a slice, where a scanner's
// reconstruction rarely interpolates) that both lie in the soft tissue's band of the histogram: a robust standard
// deviation (1.4826 times the median absolute difference, over sqrt 2), the lower of the two axes. Up to 64 slices,
// evenly spaced, are read. Correlated noise reads lower than it is, and a blur lowers it less than white noise: the
// blur found errs towards too little. `modes`: the histogram's (estimate_thresholds).
CtNoise measure_ct_noise(const Field& intensity, const IntensityModes& modes);

// The noise that remains of white noise of unit sigma after gaussian_smooth(sigma_mm) on a grid of this spacing.
double white_noise_after_blur(const Eigen::Vector3d& spacing, double sigma_mm);

}  // namespace facehex
