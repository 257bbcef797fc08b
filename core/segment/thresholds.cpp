#include "core/segment/thresholds.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/util/error.h"

namespace facehex {
namespace {

constexpr int kBins = 512;
constexpr double kSmoothingBins = 2.0;  // Gaussian sigma, in bins: removes the comb of integer-valued data

// Otsu: the bin boundary maximizing the between-class variance; the middle of the run of boundaries that all reach
// it (an empty valley between the modes of a clean phantom).
int otsu_bin(const std::vector<double>& h) {
  double total = 0, total_moment = 0;
  for (int b = 0; b < kBins; ++b) total += h[b], total_moment += b * h[b];
  std::vector<double> between(kBins - 1, -1);
  double w0 = 0, m0 = 0;
  for (int b = 0; b < kBins - 1; ++b) {
    w0 += h[b];
    m0 += b * h[b];
    const double w1 = total - w0;
    if (w0 <= 0 || w1 <= 0) continue;
    const double mu0 = m0 / w0, mu1 = (total_moment - m0) / w1;
    between[b] = w0 * w1 * (mu0 - mu1) * (mu0 - mu1);
  }
  const double best = *std::max_element(between.begin(), between.end());
  int first = -1, last = -1;
  for (int b = 0; b < kBins - 1; ++b)
    if (between[b] >= best * (1 - 1e-12)) {
      if (first < 0) first = b;
      last = b;
    }
  return (first + last) / 2;  // class 0 = bins [0, result]
}

std::vector<double> smoothed(const std::vector<double>& h) {
  const int r = static_cast<int>(std::ceil(3 * kSmoothingBins));
  std::vector<double> out(h.size(), 0);
  for (int b = 0; b < kBins; ++b) {
    double sum = 0, wsum = 0;
    for (int d = -r; d <= r; ++d) {
      if (b + d < 0 || b + d >= kBins) continue;
      const double w = std::exp(-0.5 * d * d / (kSmoothingBins * kSmoothingBins));
      sum += w * h[b + d], wsum += w;
    }
    out[b] = sum / wsum;
  }
  return out;
}

// The thresholds from the histogram of the voxels above `floor` (all of them when floor is -infinity), and the modes
// they lie between in `modes`; nothing when that histogram has no separate air and soft-tissue peaks.
std::optional<TissueThresholds> thresholds_above(const std::vector<float>& data, double floor, double lo, double hi,
                                                 BoneThresholdRule rule, IntensityModes* modes, std::string* problem) {
  const double width = (hi - lo) / kBins;
  std::vector<double> h(kBins, 0);
  for (float v : data)
    if (v > floor) h[std::min(static_cast<int>((v - lo) / width), kBins - 1)] += 1;
  auto centre = [&](double bin) { return lo + (bin + 0.5) * width; };

  const int split = otsu_bin(h);
  const std::vector<double> s = smoothed(h);
  const int air = static_cast<int>(std::max_element(s.begin(), s.begin() + split + 1) - s.begin());
  const int tissue = static_cast<int>(std::max_element(s.begin() + split + 1, s.end()) - s.begin());
  if (tissue - air < 3 || s[tissue] <= 0 || s[air] <= 0) {
    *problem =
        "no separate air and soft-tissue peaks in the intensity histogram; give the skin and bone thresholds "
        "explicitly";
    return std::nullopt;
  }
  *modes = {centre(air), centre(tissue)};
  TissueThresholds t;
  t.skin = 0.5 * (centre(air) + centre(tissue));

  int tail = tissue;
  while (tail < kBins - 1 && s[tail] >= kBoneTailFraction * s[tissue]) ++tail;
  t.bone = centre(tail);
  if (rule == BoneThresholdRule::peak_width && tail < kBins - 1) {
    // The upper half-width at half maximum, interpolated between the bins about it.
    int half = tissue + 1;
    while (s[half] >= 0.5 * s[tissue]) ++half;  // within the tail, which is below half the peak
    const double over = (s[half - 1] - 0.5 * s[tissue]) / (s[half - 1] - s[half]);
    const double half_width = (half - 1 + over - tissue) * width;
    t.bone = centre(tissue) + half_width * std::sqrt(std::log(1 / kBoneTailFraction) / std::log(2.0));
  }
  if (tail >= kBins - 1) {
    *problem =
        "the soft-tissue peak does not fall off before the maximum intensity (no bone?); give the bone threshold "
        "explicitly";
    return std::nullopt;
  }
  return t;
}

}  // namespace

TissueThresholds estimate_thresholds(const Field& intensity, BoneThresholdRule rule, IntensityModes* modes) {
  IntensityModes found;
  if (!modes) modes = &found;
  if (intensity.data.empty()) throw Error("thresholds", "the CT volume is empty");
  const auto [lo_it, hi_it] = std::minmax_element(intensity.data.begin(), intensity.data.end());
  const double lo = *lo_it, hi = *hi_it;
  if (!(hi > lo)) throw Error("thresholds", "the CT volume has a single intensity; give the thresholds explicitly");
  // A scanner fills what lies outside its field of view with one value below air: without those voxels the air peak
  // is the air's; a volume whose air is that one value (a clean phantom) keeps them.
  std::string problem;
  if (const auto t = thresholds_above(intensity.data, lo, lo, hi, rule, modes, &problem)) return *t;
  if (const auto t =
          thresholds_above(intensity.data, -std::numeric_limits<double>::infinity(), lo, hi, rule, modes, &problem))
    return *t;
  throw Error("thresholds", problem);
}

}  // namespace facehex
