#pragma once
// Meshes and helpers shared by the FE export tests (*export*_test.cpp).
#include <Eigen/Core>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/mesh/mesh.h"
#include "core/mesh/sides.h"
#include "tests/core/test_meshes.h"

namespace facehex::test {

// A slab [0,12] x [0,5] x [0,9] mm (x lateral, y depth from bone y=0 to skin y=5, z up) of 3 x 2 x 3 hexes with
// "side_mask" (hex_box) and "uvw" = (x/12, z/9, y/5). In the last column (x > 8) the bottom and top layers are split
// into two wedges per hex, listed with different rotations so that, over the boundary, every local face of both cell
// types (Abaqus S1..S6 of C3D8, S1..S5 of C3D6) lies on some side. All cells positively oriented (mesh.h).
inline VolumeMesh hex_wedge_slab() {
  const int nx = 3, ny = 2, nz = 3;
  const VolumeMesh box = hex_box(nx, ny, nz, 12, 5, 9);
  VolumeMesh m;
  m.V = box.V;
  m.point_data = box.point_data;
  Eigen::MatrixXd uvw(m.V.rows(), 3);
  uvw << m.V.col(0) / 12, m.V.col(2) / 9, m.V.col(1) / 5;
  m.point_data["uvw"] = uvw;
  std::vector<std::array<int, 8>> cells;
  int c = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i, ++c) {
        const Eigen::RowVectorXi h = box.C.row(c);
        if (i == nx - 1 && k != 1) {
          // hex bottom (0,1,2,3) has its normal towards the top: a VTK wedge lists its bottom triangle reversed.
          cells.push_back({h(0), h(2), h(1), h(4), h(6), h(5), -1, -1});
          cells.push_back({h(3), h(2), h(0), h(7), h(6), h(4), -1, -1});  // (0,3,2) rotated
        } else {
          cells.push_back({h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7)});
        }
      }
  m.C.resize(static_cast<int>(cells.size()), 8);
  for (size_t r = 0; r < cells.size(); ++r) {
    for (int k = 0; k < 8; ++k) m.C(static_cast<int>(r), k) = cells[r][k];
    m.types.push_back(cells[r][6] < 0 ? CellType::Wedge : CellType::Hex);
  }
  return m;
}

// Runs a shell command quietly; true when it exited with status 0.
inline bool run_quietly(const std::string& command) {
  return std::system((command + " > /dev/null 2>&1").c_str()) == 0;
}

// True when `program` is on PATH.
inline bool on_path(const std::string& program) { return run_quietly("command -v " + program); }

}  // namespace facehex::test
