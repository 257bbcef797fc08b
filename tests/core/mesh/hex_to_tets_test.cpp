#include "core/mesh/hex_to_tets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "core/mesh/tet_laplacian.h"
#include "core/mesh/tet_topology.h"
#include "tests/core/test_meshes.h"

namespace facehex {
namespace {

// Renumbers the vertices randomly, so the smallest-id rule meets every diagonal configuration.
VolumeMesh shuffled(const VolumeMesh& m, unsigned seed) {
  std::vector<int> perm(m.V.rows());
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), std::mt19937(seed));
  VolumeMesh out = m;
  for (int v = 0; v < m.V.rows(); ++v) out.V.row(perm[v]) = m.V.row(v);
  for (int c = 0; c < m.C.rows(); ++c)
    for (int k = 0; k < 8; ++k)
      if (m.C(c, k) >= 0) out.C(c, k) = perm[m.C(c, k)];
  return out;
}

TEST(HexToTets, ConformingSplitOfRenumberedHexGrids) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const VolumeMesh hex = shuffled(test::hex_box(3, 2, 2, 3, 2, 2), seed);
    const AuxiliaryTets aux = split_into_tets(hex);
    ASSERT_EQ(aux.T.rows(), 6 * hex.num_cells());
    EXPECT_EQ(aux.non_positive_tets, 0);
    const Eigen::VectorXd vol = tet_volumes(hex.V, aux.T);
    EXPECT_GT(vol.minCoeff(), 0);
    EXPECT_NEAR(vol.sum(), 12.0, 1e-12);
    // Conforming: every boundary triangle lies on the box surface (an interior face seen once would be a crack),
    // and the surface is covered exactly twice per boundary quad.
    const BoundaryFaces b = boundary_faces(aux.T);
    EXPECT_EQ(b.nonmanifold_faces, 0);
    EXPECT_EQ(b.F.rows(), 2 * 2 * (3 * 2 + 3 * 2 + 2 * 2));
    for (int f = 0; f < b.F.rows(); ++f) {
      bool on_box_face = false;
      for (int d = 0; d < 3; ++d) {
        const double x0 = hex.V(b.F(f, 0), d);
        on_box_face = on_box_face || ((x0 == 0.0 || x0 == (d == 0 ? 3.0 : 2.0)) && hex.V(b.F(f, 1), d) == x0 &&
                                      hex.V(b.F(f, 2), d) == x0);
      }
      EXPECT_TRUE(on_box_face) << "seed " << seed << " face " << f;
    }
    Eigen::VectorXi component;
    EXPECT_EQ(tet_components(tet_face_neighbors(aux.T), component), 1);
  }
}

TEST(HexToTets, WedgesGiveThreeTetsOfTheirVolume) {
  // A unit cube cut into two wedges along the diagonal plane x + y = 1 ... as VTK wedges (base normal away from top).
  VolumeMesh m;
  m.V.resize(8, 3);
  m.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  m.C = Eigen::MatrixXi::Constant(2, 8, -1);
  // Triangle (0,1,3) at z=0 has normal +z, so the VTK order lists it reversed: (0,3,1), top (4,7,5).
  m.C.row(0).head(6) << 0, 3, 1, 4, 7, 5;
  m.C.row(1).head(6) << 1, 3, 2, 5, 7, 6;
  m.types = {CellType::Wedge, CellType::Wedge};
  const AuxiliaryTets aux = split_into_tets(m);
  EXPECT_EQ(aux.T.rows(), 6);
  EXPECT_EQ(aux.non_positive_tets, 0);
  EXPECT_NEAR(tet_volumes(m.V, aux.T).sum(), 1.0, 1e-12);
  EXPECT_EQ(boundary_faces(aux.T).F.rows(), 12);
}

}  // namespace
}  // namespace facehex
