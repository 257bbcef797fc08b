#include "core/segment/slice_shear.h"

#include <algorithm>
#include <cmath>

namespace facehex {
namespace {

constexpr double kOnPixel = 1e-6;  // pixels: a sample this close to a pixel centre is that pixel's value

// Where a sample lies between the pixels of one line of n: the lower pixel and the weight of the next, or none when
// it lies beyond the line.
bool bracket(double at, int n, int& lower, double& weight) {
  const double nearest = std::round(at);
  if (std::abs(at - nearest) < kOnPixel) at = nearest;
  if (at < 0 || at > n - 1) return false;
  lower = std::min(static_cast<int>(std::floor(at)), std::max(n - 2, 0));
  weight = at - lower;
  return true;
}

}  // namespace

Field unshear_slices(const Field& stacked, const std::vector<Eigen::Vector2d>& offsets, float fill) {
  const GridGeometry& in = stacked.geometry;
  Eigen::Vector2d lo = Eigen::Vector2d::Zero(), hi = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& d : offsets) lo = lo.cwiseMin(d), hi = hi.cwiseMax(d);
  GridGeometry out = in;
  out.origin.head<2>() += lo;
  for (int a = 0; a < 2; ++a)
    out.dims[a] = in.dims[a] + static_cast<int>(std::ceil((hi(a) - lo(a)) / in.spacing(a) - kOnPixel));
  Field result(out, fill);
#pragma omp parallel for schedule(static)
  for (int k = 0; k < out.dims[2]; ++k)
    for (int j = 0; j < out.dims[1]; ++j) {
      int j0 = 0;
      double wy = 0;
      if (!bracket((lo.y() - offsets[k].y()) / in.spacing(1) + j, in.dims[1], j0, wy)) continue;
      const int j1 = std::min(j0 + 1, in.dims[1] - 1);
      for (int i = 0; i < out.dims[0]; ++i) {
        int i0 = 0;
        double wx = 0;
        if (!bracket((lo.x() - offsets[k].x()) / in.spacing(0) + i, in.dims[0], i0, wx)) continue;
        const int i1 = std::min(i0 + 1, in.dims[0] - 1);
        const double low = (1 - wx) * stacked(i0, j0, k) + wx * stacked(i1, j0, k);
        const double high = (1 - wx) * stacked(i0, j1, k) + wx * stacked(i1, j1, k);
        result(i, j, k) = static_cast<float>((1 - wy) * low + wy * high);
      }
    }
  return result;
}

}  // namespace facehex
