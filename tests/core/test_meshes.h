#pragma once
// Small meshes built in code for the core tests.
#include <Eigen/Core>
#include <functional>
#include <random>
#include <vector>

#include "core/mesh/hex_to_tets.h"
#include "core/mesh/mesh.h"
#include "core/mesh/sides.h"

namespace facehex::test {

// A box [0,sx]x[0,sy]x[0,sz] as an nx x ny x nz grid of hexahedra (VTK order, positively oriented), with
// "side_mask" set from the box faces: x=0 -> u0, x=sx -> u1, y=0 -> w0, y=sy -> w1, z=0 -> v0, z=sz -> v1.
// (The face-like convention: +x lateral, +y outward (anterior), +z up.)
// The index of hex_box's grid vertex (i, j, k).
inline int hex_box_vertex(int nx, int ny, int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; }

inline VolumeMesh hex_box(int nx, int ny, int nz, double sx = 1, double sy = 1, double sz = 1) {
  VolumeMesh m;
  auto id = [&](int i, int j, int k) { return hex_box_vertex(nx, ny, i, j, k); };
  m.V.resize((nx + 1) * (ny + 1) * (nz + 1), 3);
  Eigen::MatrixXd mask = Eigen::MatrixXd::Zero(m.V.rows(), 1);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        m.V.row(id(i, j, k)) << sx * i / nx, sy * j / ny, sz * k / nz;
        int bits = 0;
        if (i == 0) bits |= side_bit(U0);
        if (i == nx) bits |= side_bit(U1);
        if (j == 0) bits |= side_bit(W0);
        if (j == ny) bits |= side_bit(W1);
        if (k == 0) bits |= side_bit(V0);
        if (k == nz) bits |= side_bit(V1);
        mask(id(i, j, k)) = bits;
      }
  m.point_data[kSideMaskArray] = mask;
  m.C.resize(nx * ny * nz, 8);
  int c = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        m.C.row(c++) << id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
            id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1);
  m.types.assign(m.C.rows(), CellType::Hex);
  return m;
}

// hex_box without the cells (i, j, k) that `removed` picks (the box's side labels kept: the walls of what is removed
// lie on no side; a tunnel from back to front is an opening through the shell).
inline VolumeMesh hex_box_without(int nx, int ny, int nz, double sx, double sy, double sz,
                                  const std::function<bool(int i, int j, int k)>& removed) {
  const VolumeMesh hex = hex_box(nx, ny, nz, sx, sy, sz);
  std::vector<int> kept;
  for (int c = 0, k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i, ++c)
        if (!removed(i, j, k)) kept.push_back(c);
  VolumeMesh cut = hex;
  cut.C.resize(static_cast<Eigen::Index>(kept.size()), 8);
  for (size_t c = 0; c < kept.size(); ++c) cut.C.row(static_cast<Eigen::Index>(c)) = hex.C.row(kept[c]);
  cut.types.assign(kept.size(), CellType::Hex);
  return cut;
}

// hex_box_without's cells split into tets, with the box's side labels.
inline VolumeMesh tet_box_without(int nx, int ny, int nz, double sx, double sy, double sz,
                                  const std::function<bool(int i, int j, int k)>& removed) {
  const VolumeMesh cut = hex_box_without(nx, ny, nz, sx, sy, sz, removed);
  VolumeMesh tets = VolumeMesh::from_tets(cut.V, split_into_tets(cut).T);
  tets.point_data = cut.point_data;
  return tets;
}

// Moves interior vertices randomly by up to `amount` (in units of the smallest cell edge) so meshes are irregular.
inline void jitter_interior(VolumeMesh& m, double amount, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-amount, amount);
  const Eigen::RowVector3d lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
  for (int v = 0; v < m.V.rows(); ++v) {
    bool interior = true;
    for (int k = 0; k < 3; ++k) interior = interior && m.V(v, k) > lo(k) + 1e-12 && m.V(v, k) < hi(k) - 1e-12;
    if (interior)
      for (int k = 0; k < 3; ++k) m.V(v, k) += d(rng);
  }
}

}  // namespace facehex::test
