#include "core/fields/param_health.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <array>
#include <vector>

#include "core/mesh/hex_to_tets.h"
#include "tests/core/test_meshes.h"

namespace facehex {
namespace {

using Corners = std::array<Eigen::RowVector3d, 4>;

// Tets that share no vertex, each given by the (u, v, w) of its four corners; vertex 4t+i is corner i of tet t.
struct ParamTets {
  Eigen::MatrixXi T;
  Eigen::MatrixXd uvw;
  Eigen::MatrixXi fixed;  // #V x 3, all zero until set
};

ParamTets param_tets(const std::vector<Corners>& tets) {
  ParamTets p;
  const int n = static_cast<int>(tets.size());
  p.T.resize(n, 4);
  p.uvw.resize(4 * n, 3);
  for (int t = 0; t < n; ++t)
    for (int i = 0; i < 4; ++i) {
      p.T(t, i) = 4 * t + i;
      p.uvw.row(4 * t + i) = tets[t][i];
    }
  p.fixed = Eigen::MatrixXi::Zero(4 * n, 3);
  return p;
}

// A positive tet of the unit cube (volume 1/6 * s^3), shifted by `at`.
Corners positive(double s = 0.2, const Eigen::RowVector3d& at = Eigen::RowVector3d::Constant(0.1)) {
  return {at, at + Eigen::RowVector3d(s, 0, 0), at + Eigen::RowVector3d(0, s, 0), at + Eigen::RowVector3d(0, 0, s)};
}
Corners inverted(double s = 0.2) {  // two corners swapped
  Corners c = positive(s);
  std::swap(c[1], c[2]);
  return c;
}
// Four corners on the plane w = w0 (a flat parametric image).
Corners flat_in_w(double w0) {
  return {Eigen::RowVector3d(0.1, 0.1, w0), Eigen::RowVector3d(0.5, 0.1, w0), Eigen::RowVector3d(0.1, 0.5, w0),
          Eigen::RowVector3d(0.4, 0.4, w0)};
}

TEST(ParamHealth, TheIdentityMapOfATetrahedralizedCubeIsHealthy) {
  const VolumeMesh box = test::hex_box(3, 3, 3);
  const AuxiliaryTets tets = split_into_tets(box);
  const ParamHealth h = parameterization_health(tets.T, box.V);
  EXPECT_EQ(h.tets, 27 * 6);
  EXPECT_EQ(h.orientation, 1);
  EXPECT_EQ(h.inverted, 0);
  EXPECT_EQ(h.degenerate, 0);
  EXPECT_EQ(h.flat_by_constraint, 0);
  EXPECT_EQ(h.outside_cube, 0);
  EXPECT_TRUE(h.inverted_tets.empty());
  EXPECT_TRUE(h.ok());
}

TEST(ParamHealth, AMirroredMapHasNegativeOrientationAndIsStillHealthy) {
  const VolumeMesh box = test::hex_box(2, 2, 2);
  Eigen::MatrixXd uvw = box.V;
  uvw.col(0) = 1.0 - uvw.col(0).array();  // u = 1 - x: every parametric volume is negative
  const ParamHealth h = parameterization_health(split_into_tets(box).T, uvw);
  EXPECT_EQ(h.orientation, -1);
  EXPECT_EQ(h.inverted, 0);
  EXPECT_EQ(h.outside_cube, 0);
  EXPECT_TRUE(h.ok());
}

TEST(ParamHealth, CountsInvertedAndDegenerateTets) {
  // In order: + + - + + + - (flat, accidental) +.
  ParamTets p = param_tets({positive(), positive(0.1), inverted(), positive(), positive(0.3), positive(), inverted(0.1),
                            flat_in_w(0.5), positive()});
  const ParamHealth h = parameterization_health(p.T, p.uvw, p.fixed);
  EXPECT_EQ(h.tets, 9);
  EXPECT_EQ(h.orientation, 1);
  EXPECT_EQ(h.inverted, 2);
  EXPECT_EQ(h.inverted_tets, (std::vector<int>{2, 6}));
  EXPECT_EQ(h.degenerate, 1);
  EXPECT_EQ(h.flat_by_constraint, 0);                     // nothing is fixed
  EXPECT_EQ(h.folded_tets, (std::vector<int>{2, 6, 7}));  // the inverted ones and the accidentally flat one
  EXPECT_FALSE(h.ok());

  // The majority decides the orientation: mirrored, the six positive tets are the negative majority and the two
  // inverted ones are still the inverted ones.
  p.uvw.col(0) = 1.0 - p.uvw.col(0).array();
  const ParamHealth m = parameterization_health(p.T, p.uvw, p.fixed);
  EXPECT_EQ(m.orientation, -1);
  EXPECT_EQ(m.inverted, 2);
  EXPECT_EQ(m.inverted_tets, (std::vector<int>{2, 6}));
  EXPECT_EQ(m.degenerate, 1);
}

TEST(ParamHealth, TheOrientationIsThatOfTheMajority) {
  // 3 inverted against 2 positive: the "inverted" ones are the positive ones.
  const ParamTets p = param_tets({inverted(), positive(), inverted(), positive(), inverted()});
  const ParamHealth h = parameterization_health(p.T, p.uvw);
  EXPECT_EQ(h.orientation, -1);
  EXPECT_EQ(h.inverted, 2);
  EXPECT_EQ(h.inverted_tets, (std::vector<int>{1, 3}));
}

TEST(ParamHealth, FlatTetsAreExcusedOnlyWhenOneFieldPinsAllFourCornersToOneValue) {
  // Tet 0: flat on w = 0 with all four corners fixed in w: made flat by the constraint.
  // Tet 1: flat on w = 1 with only three corners fixed in w: accidental.
  // Tet 2: flat on w = 0.5, all corners fixed in u (at different values) but w free: accidental.
  // Tets 3-5: positive.
  ParamTets p = param_tets({flat_in_w(0), flat_in_w(1), flat_in_w(0.5), positive(), positive(), positive()});
  p.fixed.block(0, 2, 4, 1).setOnes();
  p.fixed.block(4, 2, 3, 1).setOnes();
  p.fixed.block(8, 0, 4, 1).setOnes();
  const ParamHealth h = parameterization_health(p.T, p.uvw, p.fixed);
  EXPECT_EQ(h.degenerate, 3);
  EXPECT_EQ(h.flat_by_constraint, 1);
  EXPECT_EQ(h.inverted, 0);
  EXPECT_EQ(h.folded_tets, (std::vector<int>{1, 2}));  // not the one the constraint made flat
  EXPECT_FALSE(h.ok());

  // Only the constraint-made flat tet left: healthy.
  const ParamTets q = param_tets({flat_in_w(0), positive(), positive()});
  Eigen::MatrixXi fixed = Eigen::MatrixXi::Zero(12, 3);
  fixed.block(0, 2, 4, 1).setOnes();
  const ParamHealth g = parameterization_health(q.T, q.uvw, fixed);
  EXPECT_EQ(g.degenerate, 1);
  EXPECT_EQ(g.flat_by_constraint, 1);
  EXPECT_TRUE(g.ok());
  // Without the fixed flags the same tet is an accidental one.
  EXPECT_FALSE(parameterization_health(q.T, q.uvw).ok());
}

TEST(ParamHealth, DegenerateMeansTinyAgainstTheMeanVolume) {
  // A sliver 1e-14 as thick as the others is degenerate; one 1e-6 as thick is merely thin.
  Corners sliver = positive(), thin = positive();
  sliver[3] = Eigen::RowVector3d(0.1, 0.1, 0.1 + 0.2e-14);
  thin[3] = Eigen::RowVector3d(0.1, 0.1, 0.1 + 0.2e-6);
  const ParamTets p = param_tets({positive(), positive(), sliver, thin});
  const ParamHealth h = parameterization_health(p.T, p.uvw);
  EXPECT_EQ(h.degenerate, 1);
  EXPECT_EQ(h.inverted, 0);
}

TEST(ParamHealth, CountsCoordinatesOutsideTheUnitCubeBeyondTheTolerance) {
  ParamTets p = param_tets({positive(), positive()});
  p.uvw(0, 0) = -1e-8;      // outside
  p.uvw(1, 1) = 1 + 1e-8;   // outside
  p.uvw(2, 2) = -1e-10;     // within the 1e-9 tolerance
  p.uvw(3, 0) = 1 + 1e-10;  // within the tolerance
  p.uvw(5, 2) = 1.0;        // on the cube
  const ParamHealth h = parameterization_health(p.T, p.uvw);
  EXPECT_EQ(h.outside_cube, 2);
}

// outside_cube counts vertices with a coordinate outside [0, 1], not coordinates.
TEST(ParamHealth, OutsideCubeCountsVerticesNotCoordinates) {
  ParamTets p = param_tets({positive(), positive()});
  p.uvw.row(0) << -0.5, 1.5, 2.0;  // one vertex, three coordinates outside
  EXPECT_EQ(parameterization_health(p.T, p.uvw).outside_cube, 1);
}

TEST(ParamHealth, ListsAtMostTheFirstHundredInvertedTets) {
  std::vector<Corners> tets(260, inverted());
  tets.insert(tets.end(), 300, positive());  // the positive majority
  const ParamTets p = param_tets(tets);
  const ParamHealth h = parameterization_health(p.T, p.uvw);
  EXPECT_EQ(h.orientation, 1);
  EXPECT_EQ(h.inverted, 260);
  ASSERT_EQ(h.inverted_tets.size(), 100u);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(h.inverted_tets[i], i);
}

}  // namespace
}  // namespace facehex
