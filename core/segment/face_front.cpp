#include "core/segment/face_front.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace facehex {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kRayStep = 0.25;  // mm, thinner than a closed slit
constexpr int kBisections = 6;     // to kRayStep / 64

}  // namespace

FaceFront::FaceFront(const Field& ct, double skin_threshold, const HeadTurn& frame, double x0, double x1, double z0,
                     double z1, double y_start, double y_stop)
    : x0_(x0),
      z0_(z0),
      nx_(static_cast<int>(std::lround((x1 - x0) / kGrid)) + 1),
      nz_(static_cast<int>(std::lround((z1 - z0) / kGrid)) + 1),
      y_(static_cast<size_t>(nx_) * nz_, kNaN) {
  const GridGeometry& g = ct.geometry;
  const ModelFromHead to_model(frame);
  const auto skin = [&](double x, double y, double z) {
    const Eigen::Vector3d p = to_model(Eigen::Vector3d(x, y, z));
    for (int a = 0; a < 3; ++a)
      if (p(a) < g.lower(a) || p(a) > g.upper(a)) return false;
    return sample(ct, p) >= skin_threshold;
  };
  const int steps = static_cast<int>(std::floor((y_start - y_stop) / kRayStep));
#pragma omp parallel for schedule(dynamic)
  for (int k = 0; k < nz_; ++k)
    for (int i = 0; i < nx_; ++i) {
      const double x = x0 + i * kGrid, z = z0 + k * kGrid;
      if (skin(x, y_start, z)) continue;
      for (int s = 1; s <= steps; ++s) {
        double outside = y_start - (s - 1) * kRayStep, inside = y_start - s * kRayStep;
        if (!skin(x, inside, z)) continue;
        for (int b = 0; b < kBisections; ++b) {
          const double mid = 0.5 * (outside + inside);
          (skin(x, mid, z) ? inside : outside) = mid;
        }
        y_[static_cast<size_t>(k) * nx_ + i] = 0.5 * (outside + inside);
        break;
      }
    }
}

double FaceFront::operator()(double x, double z) const {
  const double gx = (x - x0_) / kGrid, gz = (z - z0_) / kGrid;
  if (!(gx >= 0 && gx <= nx_ - 1 && gz >= 0 && gz <= nz_ - 1)) return kNaN;
  const int i = std::min(static_cast<int>(gx), nx_ - 2), k = std::min(static_cast<int>(gz), nz_ - 2);
  const double fx = gx - i, fz = gz - k;
  const auto at = [&](int a, int b) { return y_[static_cast<size_t>(k + b) * nx_ + i + a]; };
  return at(0, 0) * (1 - fx) * (1 - fz) + at(1, 0) * fx * (1 - fz) + at(0, 1) * (1 - fx) * fz + at(1, 1) * fx * fz;
}

double FaceFront::mean_across(double x, double half_width, double z) const {
  double sum = 0;
  int columns = 0;
  for (double dx = -half_width; dx <= half_width + 1e-9; dx += kGrid, ++columns) sum += (*this)(x + dx, z);
  return sum / columns;
}

}  // namespace facehex
