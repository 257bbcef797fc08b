#include "core/shape/corner_energy.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <random>
#include <vector>

#include "core/mesh/corner_jacobian.h"
#include "core/shape/cell_bounds.h"
#include "tests/core/test_meshes.h"

namespace facehex {
namespace {

// A corner matrix: the ideal corner of a hex, stretched and sheared by a random amount, positively oriented.
Eigen::Matrix3d random_corner(std::mt19937& rng, double distortion) {
  std::uniform_real_distribution<double> u(-distortion, distortion);
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) A(i, j) += u(rng);
  return A;
}

// The node coefficient patterns of corner_energy.h: a corner node, an edge's far node, an interior sample's weights.
std::vector<Eigen::Vector3d> coefficients() {
  return {Eigen::Vector3d::Constant(-1), Eigen::Vector3d::UnitY(), Eigen::Vector3d(0.3, -0.6, 0.45)};
}

TEST(CornerEnergy, NodeGradientAndHessianMatchFiniteDifferences) {
  std::mt19937 rng(3);
  for (const double delta2 : {0.0, 1e-3})
    for (const double power : {1.0, 3.0})
      for (int trial = 0; trial < 20; ++trial) {
        const Eigen::Matrix3d A0 = random_corner(rng, 0.4);
        const Eigen::Matrix3d Winv = random_corner(rng, 0.3).inverse();
        const CornerEnergy energy{delta2, power};
        for (const Eigen::Vector3d& c : coefficients()) {
          Eigen::Vector3d g;
          Eigen::Matrix3d H;
          const double e = energy.node(A0, Winv, c, g, H);
          ASSERT_TRUE(std::isfinite(e));
          EXPECT_NEAR(e, energy(A0, Winv), 1e-12 * e);
          const double h = 1e-6;
          for (int k = 0; k < 3; ++k) {
            const Eigen::Vector3d step = h * Eigen::Vector3d::Unit(k);
            const Eigen::Matrix3d Ap = A0 + step * c.transpose(), Am = A0 - step * c.transpose();
            EXPECT_NEAR(g(k), (energy(Ap, Winv) - energy(Am, Winv)) / (2 * h), 1e-5 * (1 + std::abs(g(k))));
            Eigen::Vector3d gp, gm;
            Eigen::Matrix3d unused;
            energy.node(Ap, Winv, c, gp, unused);
            energy.node(Am, Winv, c, gm, unused);
            const Eigen::Vector3d column = (gp - gm) / (2 * h);
            EXPECT_LT((H.col(k) - column).norm(), 1e-5 * (1 + H.norm())) << "delta2 " << delta2 << " power " << power;
          }
          EXPECT_LT((H - H.transpose()).norm(), 1e-10 * (1 + H.norm()));
        }
      }
}

// The summed form is the sum of the corners' own energies and derivatives; one collapsed, or (unregularized)
// inverted, corner makes the sum infinite.
TEST(CornerEnergy, SumsTheCornersAroundANode) {
  std::mt19937 rng(7);
  for (const double delta2 : {0.0, 1e-3})
    for (const double power : {1.0, 2.5}) {
      const CornerEnergy energy{delta2, power};
      std::vector<Eigen::Matrix3d> S;
      std::vector<Eigen::Vector3d> w;
      double expected = 0;
      Eigen::Vector3d expected_g = Eigen::Vector3d::Zero();
      Eigen::Matrix3d expected_H = Eigen::Matrix3d::Zero();
      for (int i = 0; i < 9; ++i) {
        const Eigen::Matrix3d A = random_corner(rng, 0.4), Winv = random_corner(rng, 0.3).inverse();
        const Eigen::Vector3d c = coefficients()[i % 3];
        Eigen::Vector3d g;
        Eigen::Matrix3d H;
        expected += energy.node(A, Winv, c, g, H);
        expected_g += g;
        expected_H += H;
        S.push_back(A * Winv);
        w.push_back(Winv.transpose() * c);
      }
      Eigen::Vector3d g;
      Eigen::Matrix3d H;
      const double e = energy.sum(S.data(), w.data(), 9, g, H);
      EXPECT_NEAR(e, expected, 1e-12 * expected);
      EXPECT_NEAR(energy.sum(S.data(), 9), expected, 1e-12 * expected);
      EXPECT_LT((g - expected_g).norm(), 1e-10 * (1 + g.norm()));
      EXPECT_LT((H - expected_H).norm(), 1e-10 * (1 + H.norm()));
      S[4].setZero();
      EXPECT_TRUE(std::isinf(energy.sum(S.data(), 9)));
      EXPECT_TRUE(std::isinf(energy.sum(S.data(), w.data(), 9, g, H)));
      S[4] = Eigen::Matrix3d::Identity();
      S[4](2, 2) = -0.5;
      EXPECT_EQ(std::isinf(energy.sum(S.data(), 9)), delta2 == 0);
    }
}

TEST(CornerEnergy, IsOneAndFlatAtTheTargetShapeWhateverItsSizeAndRotation) {
  std::mt19937 rng(5);
  const Eigen::Matrix3d W = random_corner(rng, 0.3);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -1).normalized()).toRotationMatrix();
  const Eigen::Matrix3d A = 2.5 * R * W;  // W's shape, larger and rotated
  Eigen::Vector3d g;
  Eigen::Matrix3d H;
  const double e = CornerEnergy{}.node(A, W.inverse(), Eigen::Vector3d::Constant(-1), g, H);
  EXPECT_NEAR(e, 1, 1e-12);
  EXPECT_LT(g.norm(), 1e-12);
  // A minimum: the Hessian there is positive semi-definite.
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(H).eigenvalues().minCoeff(), -1e-12);
  // Any other shape costs more.
  EXPECT_GT(CornerEnergy{}(A + 0.1 * Eigen::Matrix3d::Identity(), W.inverse()), 1 + 1e-6);
}

// Without regularization the energy is the inverse mean ratio eta = |S|^2 / (3 det(S)^(2/3)) to the given power,
// for the whole powers the solvers use and for fractional ones.
TEST(CornerEnergy, IsTheInverseMeanRatioToItsPower) {
  std::mt19937 rng(11);
  for (const double power : {1.0, 2.0, 8.0, 2.5, 40.0})
    for (int trial = 0; trial < 10; ++trial) {
      const Eigen::Matrix3d A = random_corner(rng, 0.4), Winv = random_corner(rng, 0.3).inverse();
      const Eigen::Matrix3d S = A * Winv;
      ASSERT_GT(S.determinant(), 0);
      const double eta = S.squaredNorm() / (3 * std::cbrt(S.determinant() * S.determinant()));
      const double expected = std::pow(eta, power);
      const CornerEnergy energy{0, power};
      EXPECT_NEAR(energy(A, Winv), expected, 1e-12 * expected) << "power " << power;
    }
}

TEST(CornerEnergy, AnInvertedCornerIsInfiniteWithoutRegularizationAndFiniteWithIt) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  A(2, 2) = -0.5;
  EXPECT_TRUE(std::isinf(CornerEnergy{}(A, Eigen::Matrix3d::Identity())));
  const double regularized = CornerEnergy{1e-4, 1}(A, Eigen::Matrix3d::Identity());
  EXPECT_TRUE(std::isfinite(regularized));
  // ... and larger than any positively oriented corner's there: minimizing pushes it back.
  A(2, 2) = 0.5;
  const CornerEnergy regularization{1e-4, 1};
  EXPECT_GT(regularized, regularization(A, Eigen::Matrix3d::Identity()));
}

TEST(CornerTarget, KeepsTheTargetsShapeOrMovesItToTheIdealsOrFallsBackOnAFlatOne) {
  const Eigen::Matrix3d& ideal = ideal_corner_inverse(CellType::Hex, 0);
  Eigen::Matrix3d W = ideal.inverse();
  W.col(0) *= 2;  // a box corner twice as long in one direction
  EXPECT_NEAR(CornerEnergy{}(W, target_corner_inverse(W, ideal, 0)), 1, 1e-12);
  EXPECT_GT(CornerEnergy{}(W, target_corner_inverse(W, ideal, 1)), 1.05);
  EXPECT_NEAR(CornerEnergy{}(ideal.inverse(), target_corner_inverse(W, ideal, 1)), 1, 1e-12);
  Eigen::Matrix3d flat = W;
  flat.col(2) *= 1e-3;
  EXPECT_EQ(target_corner_inverse(flat, ideal, 0), ideal);
}

TEST(CellBounds, CountsInvertedAndBadCellsAgainstTheirOwnBound) {
  VolumeMesh m = test::hex_box(2, 1, 1, 2, 1, 1);  // two unit cubes along x
  UntangleOptions options;
  options.min_scaled_jacobian = 0.5;
  const CellBounds plain(m, options);
  EXPECT_EQ(plain.count(m).bad, 0);
  // Shear the top of the cell at x in [1, 2] sideways: valid, but its scaled Jacobian falls below 0.5.
  for (int v = 0; v < m.num_vertices(); ++v)
    if (m.V(v, 0) > 1.5 && m.V(v, 2) > 0.5) m.V(v, 0) += 2;
  ASSERT_LT(scaled_jacobian(CellType::Hex, cell_nodes(m, 1)), 0.5);
  ASSERT_GT(scaled_jacobian(CellType::Hex, cell_nodes(m, 1)), 0.1);
  const CellBounds::Counts counts = plain.count(m);
  EXPECT_EQ(counts.inverted, 0);
  EXPECT_EQ(counts.bad, 1);
  EXPECT_TRUE(plain.is_bad(m, 1));
  // A cell already that poor in the mesh it came from is held to half its own scaled Jacobian instead.
  options.reference_scaled_jacobian = Eigen::VectorXd::Constant(2, counts.min_scaled_jacobian);
  const CellBounds own(m, options);
  EXPECT_EQ(own.count(m).bad, 0);
  // Pull one node through the opposite face: inverted.
  m.V(m.C(1, 6), 0) = -1;
  EXPECT_EQ(own.count(m).inverted, 1);
  options.reference_scaled_jacobian = Eigen::VectorXd::Ones(3);
  EXPECT_THROW(CellBounds(m, options), std::exception);
}

}  // namespace
}  // namespace facehex
