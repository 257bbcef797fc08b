#pragma once
// The mirror plane of a sampled front, shared by the CT's anatomy (core/segment/face_anatomy.h) and the skin's
// landmarks (core/face/face_landmarks.h).
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace facehex {

// `front[i]` is the depth (most anterior y) at x = origin + i * step, NaN where there is nothing. Returns the c that
// minimises the mean squared difference between front(c + s) and front(c - s) - a s (the linear term a s absorbs a
// head turned about the vertical axis) over s in (0, reach], searched every step / 2 outwards from x0 within
// +-search (so that among equal fronts, a flat one, the nearest to x0 wins); none if at no c are at least 60 % of
// the pairs inside.
inline std::optional<double> mirror_centre(const std::vector<double>& front, double origin, double step, double x0,
                                           double search, double reach) {
  const auto at = [&](double x) {
    const double t = (x - origin) / step;
    const int i = static_cast<int>(std::floor(t));
    if (i < 0 || i + 1 >= static_cast<int>(front.size())) return std::numeric_limits<double>::quiet_NaN();
    return front[i] + (t - i) * (front[i + 1] - front[i]);
  };
  std::optional<double> best;
  double best_cost = std::numeric_limits<double>::infinity();
  const double half = 0.5 * step;
  for (int t = 0; t <= 2 * static_cast<int>(search / half); ++t) {
    const double c = x0 + (t % 2 ? 1 : -1) * ((t + 1) / 2) * half;
    std::vector<std::pair<double, double>> pairs;  // (s, difference)
    double ss = 0, sr = 0;
    for (double s = step; s <= reach; s += step) {
      const double r = at(c + s) - at(c - s);
      if (std::isnan(r)) continue;
      pairs.emplace_back(s, r);
      ss += s * s, sr += s * r;
    }
    if (pairs.size() < 0.6 * reach / step) continue;
    const double a = sr / ss;
    double cost = 0;
    for (const auto& [s, r] : pairs) cost += (r - a * s) * (r - a * s);
    cost /= pairs.size();
    if (cost < best_cost - 1e-9) best_cost = cost, best = c;
  }
  return best;
}

}  // namespace facehex
