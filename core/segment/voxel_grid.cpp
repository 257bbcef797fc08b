#include "core/segment/voxel_grid.h"

#include <algorithm>
#include <cmath>

namespace facehex {

std::pair<std::array<int, 3>, std::array<int, 3>> occupied_box(const Mask& mask) {
  const GridGeometry& g = mask.geometry;
  std::array<int, 3> lo = g.dims, hi = {0, 0, 0};
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i)
        if (mask(i, j, k)) {
          const int at[3] = {i, j, k};
          for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], at[a]), hi[a] = std::max(hi[a], at[a] + 1);
        }
  return {lo, hi};
}

namespace {

// The cell of the grid along axis a that holds coordinate x (clamped to the voxel centres), and x's fraction in it.
void cell_along(const GridGeometry& g, int a, double x, int& base, double& frac) {
  const double t = std::clamp((x - g.origin(a)) / g.spacing(a), 0.0, static_cast<double>(g.dims[a] - 1));
  base = std::min(static_cast<int>(std::floor(t)), std::max(g.dims[a] - 2, 0));
  frac = t - base;
}

// Trilinear interpolation in the cell at `base` with fractions `frac`.
double trilinear(const Field& field, const int base[3], const double frac[3]) {
  const GridGeometry& g = field.geometry;
  double value = 0;
  for (int c = 0; c < 8; ++c) {
    const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
    const double w = (di ? frac[0] : 1 - frac[0]) * (dj ? frac[1] : 1 - frac[1]) * (dk ? frac[2] : 1 - frac[2]);
    if (w == 0) continue;
    value += w * field(std::min(base[0] + di, g.dims[0] - 1), std::min(base[1] + dj, g.dims[1] - 1),
                       std::min(base[2] + dk, g.dims[2] - 1));
  }
  return value;
}

}  // namespace

double sample(const Field& field, const Eigen::Vector3d& p) {
  int base[3];
  double frac[3];
  for (int a = 0; a < 3; ++a) cell_along(field.geometry, a, p(a), base[a], frac[a]);
  return trilinear(field, base, frac);
}

GridGeometry resampled_geometry(const GridGeometry& g, double spacing) {
  GridGeometry out;
  out.origin = g.origin;
  out.spacing = Eigen::Vector3d::Constant(spacing);
  for (int a = 0; a < 3; ++a)
    out.dims[a] = static_cast<int>(std::floor((g.upper(a) - g.lower(a)) / spacing + 1e-9)) + 1;
  return out;
}

Field resample_mapped(const Field& field, const GridGeometry& target,
                      const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& to_field, float outside) {
  const GridGeometry& g = field.geometry;
  Field out(target, outside);
#pragma omp parallel for schedule(dynamic)
  for (int k = 0; k < target.dims[2]; ++k)
    for (int j = 0; j < target.dims[1]; ++j)
      for (int i = 0; i < target.dims[0]; ++i) {
        const Eigen::Vector3d x = to_field(target.point(i, j, k));
        bool inside = true;
        for (int a = 0; a < 3; ++a)
          inside = inside && x(a) >= g.lower(a) - 0.5 * g.spacing(a) && x(a) <= g.upper(a) + 0.5 * g.spacing(a);
        if (inside) out(i, j, k) = static_cast<float>(sample(field, x));
      }
  return out;
}

Field resample(const Field& field, const GridGeometry& target) {
  // sample() at each voxel centre, with each axis's cell and fraction found once per index along it (a centre's
  // coordinate along an axis depends on that index only).
  std::array<std::vector<int>, 3> base;
  std::array<std::vector<double>, 3> frac;
  for (int a = 0; a < 3; ++a) {
    base[a].resize(target.dims[a]);
    frac[a].resize(target.dims[a]);
    for (int n = 0; n < target.dims[a]; ++n)
      cell_along(field.geometry, a, target.origin(a) + n * target.spacing(a), base[a][n], frac[a][n]);
  }
  Field out(target, 0.0f);
  // Every voxel is sampled on its own: the slices split over threads with the same result.
#pragma omp parallel for schedule(static)
  for (int k = 0; k < target.dims[2]; ++k)
    for (int j = 0; j < target.dims[1]; ++j)
      for (int i = 0; i < target.dims[0]; ++i) {
        const int at[3] = {base[0][i], base[1][j], base[2][k]};
        const double f[3] = {frac[0][i], frac[1][j], frac[2][k]};
        out(i, j, k) = static_cast<float>(trilinear(field, at, f));
      }
  return out;
}

std::vector<double> gaussian_kernel(double sigma) {
  const int r = static_cast<int>(std::ceil(3 * sigma));
  std::vector<double> kernel(2 * r + 1);
  double total = 0;
  for (int d = -r; d <= r; ++d) total += kernel[d + r] = std::exp(-0.5 * d * d / (sigma * sigma));
  for (double& w : kernel) w /= total;
  return kernel;
}

Field gaussian_smooth(const Field& field, double sigma) {
  Field out = field;
  if (sigma <= 0) return out;
  const GridGeometry& g = field.geometry;
  const size_t nx = static_cast<size_t>(g.dims[0]);
  for (int axis = 0; axis < 3; ++axis) {
    const std::vector<double> kernel = gaussian_kernel(sigma / g.spacing(axis));
    const int r = static_cast<int>(kernel.size() / 2);
    const Field in = out;
    const int len = g.dims[axis];
    // Each output voxel sums its taps in the kernel's order, beyond the grid the border value: along x within a
    // padded copy of the row, along y and z whole rows at once (memory order, which the compiler vectorizes).
    if (axis == 0) {
#pragma omp parallel
      {
        std::vector<float> line(static_cast<size_t>(len) + 2 * r);
#pragma omp for schedule(static)
        for (int row = 0; row < g.dims[1] * g.dims[2]; ++row) {
          const float* src = in.data.data() + row * nx;
          for (int x = -r; x < len + r; ++x) line[x + r] = src[std::clamp(x, 0, len - 1)];
          float* dst = out.data.data() + row * nx;
          for (int x = 0; x < len; ++x) {
            double sum = 0;
            for (int d = -r; d <= r; ++d) sum += kernel[d + r] * line[x + d + r];
            dst[x] = static_cast<float>(sum);
          }
        }
      }
      continue;
    }
#pragma omp parallel
    {
      std::vector<double> sum(nx);
#pragma omp for schedule(static)
      for (int k = 0; k < g.dims[2]; ++k)
        for (int j = 0; j < g.dims[1]; ++j) {
          std::fill(sum.begin(), sum.end(), 0.0);
          for (int d = -r; d <= r; ++d) {
            const int at = std::clamp((axis == 1 ? j : k) + d, 0, len - 1);
            const float* src = in.data.data() + (axis == 1 ? g.index(0, at, k) : g.index(0, j, at));
            for (size_t i = 0; i < nx; ++i) sum[i] += kernel[d + r] * src[i];
          }
          float* dst = out.data.data() + g.index(0, j, k);
          for (size_t i = 0; i < nx; ++i) dst[i] = static_cast<float>(sum[i]);
        }
    }
  }
  return out;
}

}  // namespace facehex
