#include "core/util/blas_threads.h"

#include <gtest/gtest.h>

#include "core/fields/harmonic_solver.h"
#include "core/mesh/hex_to_tets.h"
#include "core/mesh/tet_laplacian.h"
#include "tests/core/test_meshes.h"

namespace facehex {
namespace {

// A harmonic field on a box with u = x on its faces: the factorization it makes loads CHOLMOD, and with it the BLAS
// Debian chose (OpenBLAS when scripts/install-deps.sh installed it).
Eigen::VectorXd box_field() {
  const VolumeMesh box = test::hex_box(4, 4, 4, 4, 4, 4);
  const Eigen::MatrixXi T = split_into_tets(box).T;
  DirichletConditions faces;
  for (int v = 0; v < box.num_vertices(); ++v) {
    const Eigen::RowVector3d x = box.V.row(v);
    if ((x.array() == 0).any() || (x.array() == 4).any()) {
      faces.vertices.push_back(v);
      faces.values.push_back(x.x());
    }
  }
  return HarmonicSolver(cotangent_stiffness(box.V, T), faces).solve_laplace();
}

TEST(BlasThreads, TheFactorizationsRunOnOneThreadAndTheCountComesBack) {
  const Eigen::VectorXd u = box_field();
  EXPECT_NEAR(u.maxCoeff(), 4.0, 1e-12);
  if (blas_threads() == 0) GTEST_SKIP() << "the BLAS in use is not OpenBLAS";
  const int before = blas_threads();
  set_blas_threads(2);
  ASSERT_EQ(blas_threads(), 2);
  {
    const SingleThreadedBlas single;
    EXPECT_EQ(blas_threads(), 1);
  }
  EXPECT_EQ(blas_threads(), 2);
  EXPECT_EQ(box_field(), u);  // the solver's own guard restored the count too
  EXPECT_EQ(blas_threads(), 2);
  set_blas_threads(before);
}

}  // namespace
}  // namespace facehex
