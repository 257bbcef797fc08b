#include "core/segment/distance_transform.h"

#include <cmath>
#include <limits>

namespace facehex {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// One pass along a line of n samples spaced h apart: d[x] = min_q (h (x - q))^2 + f[q], arg[x] = the minimizing q.
// Buffers v (parabola apexes) and z (envelope breakpoints) are the caller's to avoid reallocating per line.
void lower_envelope(const std::vector<double>& f, int n, double h, std::vector<double>& d, std::vector<int>& arg,
                    std::vector<int>& v, std::vector<double>& z) {
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (f[q] == kInf) continue;
    const double fq = f[q] + (h * q) * (h * q);
    while (k >= 0) {
      const int p = v[k];
      const double s = (fq - (f[p] + (h * p) * (h * p))) / (2 * h * (q - p));
      if (s <= z[k]) {
        --k;
        continue;
      }
      z[k + 1] = s;
      break;
    }
    if (k < 0) z[0] = -kInf;
    v[++k] = q;
    z[k + 1] = kInf;
  }
  if (k < 0) {
    for (int x = 0; x < n; ++x) d[x] = kInf, arg[x] = -1;
    return;
  }
  int j = 0;
  for (int x = 0; x < n; ++x) {
    while (z[j + 1] < h * x) ++j;
    const double dx = h * (x - v[j]);
    d[x] = dx * dx + f[v[j]];
    arg[x] = v[j];
  }
}

}  // namespace

Field distance_to(const Mask& features, std::vector<std::int64_t>* nearest) {
  const GridGeometry& g = features.geometry;
  const size_t n = g.size();
  std::vector<double> sq(n);
  std::vector<std::int64_t> near;
  if (nearest) near.resize(n);
  for (size_t i = 0; i < n; ++i) {
    sq[i] = features.data[i] ? 0.0 : kInf;
    if (nearest) near[i] = features.data[i] ? static_cast<std::int64_t>(i) : -1;
  }
  const size_t stride[3] = {1, static_cast<size_t>(g.dims[0]), static_cast<size_t>(g.dims[0]) * g.dims[1]};
  for (int axis = 0; axis < 3; ++axis) {
    const int len = g.dims[axis];
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    // The lines of one pass are independent: split over threads, each with its own line buffers.
#pragma omp parallel
    {
      std::vector<double> f(len), d(len), z(len + 1);
      std::vector<int> arg(len), v(len);
      std::vector<std::int64_t> line_near(nearest ? len : 0);
#pragma omp for schedule(static)
      for (int u = 0; u < g.dims[a2]; ++u)
        for (int w = 0; w < g.dims[a1]; ++w) {
          const size_t start = static_cast<size_t>(u) * stride[a2] + static_cast<size_t>(w) * stride[a1];
          for (int x = 0; x < len; ++x) {
            f[x] = sq[start + x * stride[axis]];
            if (nearest) line_near[x] = near[start + x * stride[axis]];
          }
          lower_envelope(f, len, g.spacing(axis), d, arg, v, z);
          for (int x = 0; x < len; ++x) {
            sq[start + x * stride[axis]] = d[x];
            if (nearest) near[start + x * stride[axis]] = arg[x] < 0 ? -1 : line_near[arg[x]];
          }
        }
    }
  }
  Field out(g, 0.0f);
  for (size_t i = 0; i < n; ++i) out.data[i] = static_cast<float>(std::sqrt(sq[i]));
  if (nearest) *nearest = std::move(near);
  return out;
}

}  // namespace facehex
