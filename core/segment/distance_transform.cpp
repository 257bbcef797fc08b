#include "core/segment/distance_transform.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace facehex {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kBlock = 16;  // lines along y or z taken together (consecutive in x)

// One pass along a line of n samples spaced h apart: d[x] = min_q (h (x - q))^2 + f[q], arg[x] = the minimizing q.
// Buffers v (parabola apexes) and z (envelope breakpoints) are the caller's to avoid reallocating per line.
void lower_envelope(const double* f, int n, double h, double* d, int* arg, std::vector<int>& v,
                    std::vector<double>& z) {
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

// The squared distances (mm^2) of distance_to.
std::vector<float> squared_distance_to(const Mask& features, std::vector<std::int64_t>* nearest) {
  const GridGeometry& g = features.geometry;
  const size_t n = g.size();
  std::vector<float> sq(n);
  std::vector<std::int64_t> near;
  if (nearest) near.resize(n);
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < n; ++i) {
    sq[i] = features.data[i] ? 0.0f : std::numeric_limits<float>::infinity();
    if (nearest) near[i] = features.data[i] ? static_cast<std::int64_t>(i) : -1;
  }
  const size_t stride[3] = {1, static_cast<size_t>(g.dims[0]), static_cast<size_t>(g.dims[0]) * g.dims[1]};
  // Along x the values are 0 (a feature) or infinite: each voxel's nearest feature on its line, by one scan each way,
  // is the lower envelope of parabolas of equal height (the nearer, the left one on a tie).
  const int nx = g.dims[0];
  const double hx = g.spacing(0);
#pragma omp parallel
  {
    std::vector<int> left(nx);
#pragma omp for schedule(static)
    for (size_t start = 0; start < n; start += nx) {
      int last = -1;
      for (int x = 0; x < nx; ++x) left[x] = last = features.data[start + x] ? x : last;
      int next = -1;
      for (int x = nx - 1; x >= 0; --x) {
        if (features.data[start + x]) next = x;
        const int q = left[x] >= 0 && (next < 0 || x - left[x] <= next - x) ? left[x] : next;
        if (q < 0) continue;  // no feature on the line: infinite, as initialized
        const double dx = hx * (x - q);
        sq[start + x] = static_cast<float>(dx * dx);
        if (nearest) near[start + x] = static_cast<std::int64_t>(start + q);
      }
    }
  }
  for (int axis = 1; axis < 3; ++axis) {
    const int len = g.dims[axis];
    // Lines along y and z are strided in memory: they are taken kBlock neighbours in x at a time, so that each cache
    // line read serves kBlock lines rather than one.
    const int a_outer = axis == 2 ? 1 : 2;  // the axis other than x and this one
    // The lines of one pass are independent: split over threads, each with its own line buffers.
#pragma omp parallel
    {
      const size_t block_size = static_cast<size_t>(len) * kBlock;
      std::vector<double> f(block_size), d(block_size), z(len + 1);
      std::vector<int> arg(block_size), v(len);
      std::vector<std::int64_t> line_near(nearest ? block_size : 0);
#pragma omp for schedule(static)
      for (int o = 0; o < g.dims[a_outer]; ++o)
        for (int w0 = 0; w0 < nx; w0 += kBlock) {
          const int lines = std::min(kBlock, nx - w0);
          const size_t start = static_cast<size_t>(o) * stride[a_outer] + static_cast<size_t>(w0);
          for (int x = 0; x < len; ++x)
            for (int b = 0; b < lines; ++b) {
              const size_t at = start + b + x * stride[axis];
              f[static_cast<size_t>(b) * len + x] = sq[at];
              if (nearest) line_near[static_cast<size_t>(b) * len + x] = near[at];
            }
          for (int b = 0; b < lines; ++b) {
            const size_t line = static_cast<size_t>(b) * len;
            lower_envelope(f.data() + line, len, g.spacing(axis), d.data() + line, arg.data() + line, v, z);
          }
          for (int x = 0; x < len; ++x)
            for (int b = 0; b < lines; ++b) {
              const size_t at = start + b + x * stride[axis], line = static_cast<size_t>(b) * len;
              sq[at] = static_cast<float>(d[line + x]);
              if (nearest) near[at] = arg[line + x] < 0 ? -1 : line_near[line + arg[line + x]];
            }
        }
    }
  }
  if (nearest) *nearest = std::move(near);
  return sq;
}

}  // namespace

Field distance_to(const Mask& features, std::vector<std::int64_t>* nearest) {
  const std::vector<float> sq = squared_distance_to(features, nearest);
  Field out(features.geometry, 0.0f);
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < sq.size(); ++i) out.data[i] = static_cast<float>(std::sqrt(sq[i]));
  return out;
}

Mask within_distance(const Mask& features, double radius) {
  Mask out(features.geometry, 0);
  if (radius < 0) return out;
  const std::vector<float> sq = squared_distance_to(features, nullptr);
  // Squared distances clearly below or above radius^2 decide without the square root; the few near it are decided
  // as distance_to's rounded value would be (the float's relative rounding is far below the bracket's 1e-6).
  const double below = radius * (1 - 1e-6) * radius * (1 - 1e-6), above = radius * (1 + 1e-6) * radius * (1 + 1e-6);
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < sq.size(); ++i)
    out.data[i] = sq[i] <= below || (sq[i] <= above && static_cast<float>(std::sqrt(sq[i])) <= radius);
  return out;
}

}  // namespace facehex
