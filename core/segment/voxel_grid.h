#pragma once
// A regular 3D grid of voxel values, the common currency of the segmentation steps.
//
// Conventions: voxel (i, j, k) has its centre at origin + (i, j, k) .* spacing (millimetres, physical frame of the
// CT after reorientation: +y anterior, +z superior); data is stored x fastest, then y, then z (VTK's order).
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace facehex {

struct GridGeometry {
  std::array<int, 3> dims = {0, 0, 0};
  Eigen::Vector3d spacing = Eigen::Vector3d::Ones();
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();

  size_t size() const { return static_cast<size_t>(dims[0]) * dims[1] * dims[2]; }
  size_t index(int i, int j, int k) const {
    return static_cast<size_t>(i) +
           static_cast<size_t>(dims[0]) * (static_cast<size_t>(j) + static_cast<size_t>(dims[1]) * k);
  }
  std::array<int, 3> ijk(size_t index) const {
    const int i = static_cast<int>(index % dims[0]);
    const size_t rest = index / dims[0];
    return {i, static_cast<int>(rest % dims[1]), static_cast<int>(rest / dims[1])};
  }
  Eigen::Vector3d point(int i, int j, int k) const { return origin + Eigen::Vector3d(i, j, k).cwiseProduct(spacing); }
  bool contains(int i, int j, int k) const {
    return i >= 0 && j >= 0 && k >= 0 && i < dims[0] && j < dims[1] && k < dims[2];
  }
  // Physical extent of the voxel centres: [lower(a), upper(a)] along axis a.
  double lower(int axis) const { return origin(axis); }
  double upper(int axis) const { return origin(axis) + (dims[axis] - 1) * spacing(axis); }
};

template <class T>
struct VoxelGrid {
  GridGeometry geometry;
  std::vector<T> data;

  VoxelGrid() = default;
  VoxelGrid(const GridGeometry& g, T value) : geometry(g), data(g.size(), value) {}

  T& operator()(int i, int j, int k) { return data[geometry.index(i, j, k)]; }
  T operator()(int i, int j, int k) const { return data[geometry.index(i, j, k)]; }
};

using Mask = VoxelGrid<std::uint8_t>;  // 0 = outside, 1 = inside
using Field = VoxelGrid<float>;

// The box of a mask's nonzero voxels: lo <= (i, j, k) < hi; lo = dims and hi = 0 when there are none.
std::pair<std::array<int, 3>, std::array<int, 3>> occupied_box(const Mask& mask);

// The voxels lo <= (i, j, k) < hi of a grid (within it), at the same physical positions.
template <class T>
VoxelGrid<T> crop(const VoxelGrid<T>& grid, const std::array<int, 3>& lo, const std::array<int, 3>& hi) {
  GridGeometry g = grid.geometry;
  for (int a = 0; a < 3; ++a) {
    g.dims[a] = hi[a] - lo[a];
    g.origin(a) += lo[a] * g.spacing(a);
  }
  VoxelGrid<T> out(g, T());
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) out(i, j, k) = grid(i + lo[0], j + lo[1], k + lo[2]);
  return out;
}

// Trilinear interpolation at a physical point; points beyond the voxel centres take the nearest border value.
double sample(const Field& field, const Eigen::Vector3d& p);

// The isotropic grid of the given spacing over the same physical box (from the first voxel centre).
GridGeometry resampled_geometry(const GridGeometry& g, double spacing);

// Sampled trilinearly at the voxel centres of any target grid.
Field resample(const Field& field, const GridGeometry& target);

// Sampled trilinearly at to_field(p) for each voxel centre p of the target grid, or `outside` where to_field(p) lies
// beyond the field's box by more than half a voxel: nothing was scanned there, and a border value carried outwards
// would add tissue. to_field is called from several threads.
Field resample_mapped(const Field& field, const GridGeometry& target,
                      const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& to_field, float outside);

// The normalized weights of a Gaussian of `sigma` voxels at offsets -r .. r, r = ceil(3 sigma): the blur's kernel.
std::vector<double> gaussian_kernel(double sigma);

// Separable Gaussian blur, sigma in millimetres (gaussian_kernel along each axis in turn, each voxel's taps summed in
// the kernel's order); the grid border is extended by replication.
Field gaussian_smooth(const Field& field, double sigma);

}  // namespace facehex
