#include "core/segment/ct_noise.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace facehex {
namespace {

constexpr int kMostSlices = 64;
// Half-width of the soft tissue's band, as a fraction of the contrast: at least, and at most (short of the skin
// threshold, half way to air).
constexpr double kTissueBand = 0.2, kWidestTissueBand = 0.4;

// Robust sigma of the differences along `axis` (0 or 1) between neighbours both within [lo, hi], on the slices read.
double neighbour_sigma(const Field& f, int axis, double lo, double hi) {
  const GridGeometry& g = f.geometry;
  const int slices = std::min(kMostSlices, g.dims[2]);
  const size_t step = axis == 0 ? 1 : static_cast<size_t>(g.dims[0]);
  std::vector<float> d;
  for (int s = 0; s < slices; ++s) {
    const int k = static_cast<int>((s + 0.5) * g.dims[2] / slices);
    for (int j = 0; j + (axis == 1) < g.dims[1]; ++j)
      for (int i = 0; i + (axis == 0) < g.dims[0]; ++i) {
        const size_t v = g.index(i, j, k);
        const float a = f.data[v], b = f.data[v + step];
        if (a >= lo && a <= hi && b >= lo && b <= hi) d.push_back(std::abs(a - b));
      }
  }
  if (d.empty()) return 0;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return 1.4826 * d[d.size() / 2] / std::sqrt(2.0);
}

}  // namespace

double white_noise_after_blur(const Eigen::Vector3d& spacing, double sigma_mm) {
  if (sigma_mm <= 0) return 1;
  double variance = 1;
  for (int a = 0; a < 3; ++a) {
    double sum = 0;
    for (double w : gaussian_kernel(sigma_mm / spacing(a))) sum += w * w;
    variance *= sum;
  }
  return std::sqrt(variance);
}

CtNoise measure_ct_noise(const Field& intensity, const IntensityModes& modes) {
  CtNoise n;
  n.contrast = modes.tissue - modes.air;
  if (!(n.contrast > 0)) return n;
  // A band narrow against the noise cuts its differences short: it is widened to 3 sigma of a first reading, within
  // the soft tissue's half of the contrast.
  double band = kTissueBand * n.contrast;
  for (int pass = 0; pass < 2; ++pass) {
    const double lo = modes.tissue - band, hi = modes.tissue + band;
    const double x = neighbour_sigma(intensity, 0, lo, hi), y = neighbour_sigma(intensity, 1, lo, hi);
    n.sigma = x > 0 && y > 0 ? std::min(x, y) : std::max(x, y);
    band = std::clamp(3 * n.sigma, kTissueBand * n.contrast, kWidestTissueBand * n.contrast);
  }
  const double target = kDiagnosticNoise * n.contrast;
  const Eigen::Vector3d& spacing = intensity.geometry.spacing;
  n.sigma_after = n.sigma;
  if (!(n.sigma > target)) return n;
  if (n.sigma * white_noise_after_blur(spacing, kMostDenoisingBlur) > target) {
    n.blur = kMostDenoisingBlur;
    n.sigma_after = n.sigma * white_noise_after_blur(spacing, n.blur);
    return n;
  }
  // The smallest blur that reaches the target (the remaining noise falls as the blur grows).
  double lo_blur = 0, hi_blur = kMostDenoisingBlur;
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (lo_blur + hi_blur);
    (n.sigma * white_noise_after_blur(spacing, mid) > target ? lo_blur : hi_blur) = mid;
  }
  n.blur = hi_blur;
  n.sigma_after = n.sigma * white_noise_after_blur(spacing, n.blur);
  return n;
}

}  // namespace facehex
