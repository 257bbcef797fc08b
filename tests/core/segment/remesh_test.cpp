#include "core/segment/remesh.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "core/segment/iso_surface.h"

namespace facehex {
namespace {

// A fine closed sphere (the zero level of a distance field, so marching-cubes slivers included), labelled 0 below
// z = 0.3 r and 1 above.
SurfaceMesh labelled_sphere(double r) {
  GridGeometry g;
  g.dims = {41, 41, 41};
  g.spacing = Eigen::Vector3d::Constant(2.2 * r / 40);
  g.origin = Eigen::Vector3d::Constant(-1.1 * r);
  Field phi(g, 0.0f);
  for (int k = 0; k < 41; ++k)
    for (int j = 0; j < 41; ++j)
      for (int i = 0; i < 41; ++i) phi(i, j, k) = static_cast<float>(g.point(i, j, k).norm() - r);
  SurfaceMesh s = zero_level_surface(phi);
  s.labels.resize(s.F.rows());
  for (int f = 0; f < s.F.rows(); ++f)
    s.labels(f) = (s.V(s.F(f, 0), 2) + s.V(s.F(f, 1), 2) + s.V(s.F(f, 2), 2)) / 3 > 0.3 * r;
  return s;
}

int euler_characteristic(const Eigen::MatrixXi& F) {
  std::set<int> vertices;
  std::set<std::pair<int, int>> edges;
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) vertices.insert(F(f, k)), edges.insert(std::minmax(F(f, k), F(f, (k + 1) % 3)));
  return static_cast<int>(vertices.size() - edges.size()) + static_cast<int>(F.rows());
}

TEST(Remesh, SphereGetsTargetSizedWellShapedTrianglesAndKeepsItsLabels) {
  const double r = 20, target = 3;
  const SurfaceMesh in = labelled_sphere(r);
  const SurfaceMesh out = remesh_isotropic(in, target);
  ASSERT_TRUE(is_closed_manifold(out));
  EXPECT_EQ(euler_characteristic(out.F), 2);
  ASSERT_EQ(out.labels.size(), out.F.rows());
  double sum = 0, min_angle = 180;
  int count = 0;
  for (int f = 0; f < out.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d a = out.V.row(out.F(f, k)), b = out.V.row(out.F(f, (k + 1) % 3)),
                            c = out.V.row(out.F(f, (k + 2) % 3));
      sum += (b - a).norm(), ++count;
      min_angle = std::min(min_angle, std::acos((b - a).normalized().dot((c - a).normalized())) * 180 / M_PI);
    }
  EXPECT_NEAR(sum / count, target, 0.25 * target);
  EXPECT_GT(min_angle, 15);
  for (int v = 0; v < out.V.rows(); ++v) EXPECT_NEAR(out.V.row(v).norm(), r, 0.05 * r);
  // The label boundary stays on the circle z = 0.3 r: every face's label matches the side of z = 0.3 r it is on.
  for (int f = 0; f < out.F.rows(); ++f) {
    const double z = (out.V(out.F(f, 0), 2) + out.V(out.F(f, 1), 2) + out.V(out.F(f, 2), 2)) / 3;
    if (std::abs(z - 0.3 * r) > target) {
      EXPECT_EQ(out.labels(f), z > 0.3 * r) << "face " << f;
    }
  }
}

}  // namespace
}  // namespace facehex
