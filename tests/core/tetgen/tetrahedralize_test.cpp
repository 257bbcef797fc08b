#include "core/tetgen/tetrahedralize.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <Eigen/Geometry>
#include <cerrno>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "core/util/error.h"

namespace facehex {
namespace {

// TetGen runs in child processes (the self-intersection check and the mesh at the same time): none may outlive a call.
void expect_no_process_left() {
  errno = 0;
  EXPECT_EQ(::waitpid(-1, nullptr, WNOHANG), -1);
  EXPECT_EQ(errno, ECHILD) << "a TetGen process is still running or unreaped";
}

// Axis-aligned box [0,a]x[0,b]x[0,c], outward triangles, face label 1..6 = -x,+x,-y,+y,-z,+z.
SurfaceMesh box(double a, double b, double c) {
  SurfaceMesh s;
  s.V.resize(8, 3);
  for (int i = 0; i < 8; ++i) s.V.row(i) << (i & 1 ? a : 0), (i & 2 ? b : 0), (i & 4 ? c : 0);
  s.F.resize(12, 3);
  s.F << 0, 4, 6, 0, 6, 2,  // -x
      1, 3, 7, 1, 7, 5,     // +x
      0, 1, 5, 0, 5, 4,     // -y
      2, 6, 7, 2, 7, 3,     // +y
      0, 2, 3, 0, 3, 1,     // -z
      4, 5, 7, 4, 7, 6;     // +z
  s.labels.resize(12);
  for (int f = 0; f < 12; ++f) s.labels(f) = f / 2 + 1;
  return s;
}

// Icosahedron subdivided `levels` times, projected on the sphere of radius r.
SurfaceMesh icosphere(double r, int levels) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<Eigen::Vector3d> v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                                    {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back((v[a] + v[b]) / 2);
      return mid[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& tri : f) {
      const int a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]), c = midpoint(tri[2], tri[0]);
      next.insert(next.end(), {{tri[0], a, c}, {tri[1], b, a}, {tri[2], c, b}, {a, b, c}});
    }
    f = next;
  }
  SurfaceMesh s;
  s.V.resize(static_cast<int>(v.size()), 3);
  for (size_t i = 0; i < v.size(); ++i) s.V.row(i) = r * v[i].normalized();
  s.F.resize(static_cast<int>(f.size()), 3);
  for (size_t i = 0; i < f.size(); ++i) s.F.row(i) << f[i][0], f[i][1], f[i][2];
  return s;
}

double tet_volume(const VolumeMesh& m, int t) {
  const Eigen::Vector3d p0 = m.V.row(m.C(t, 0)), p1 = m.V.row(m.C(t, 1)), p2 = m.V.row(m.C(t, 2)),
                        p3 = m.V.row(m.C(t, 3));
  return (p1 - p0).dot((p2 - p0).cross(p3 - p0)) / 6;
}

double total_volume_all_positive(const VolumeMesh& m) {
  double total = 0;
  for (int t = 0; t < m.num_cells(); ++t) {
    const double v = tet_volume(m, t);
    EXPECT_GT(v, 0) << "tet " << t;
    total += v;
  }
  return total;
}

double mean_edge_length(const VolumeMesh& m) {
  std::set<std::pair<int, int>> edges;
  for (int t = 0; t < m.num_cells(); ++t)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) edges.insert(std::minmax(m.C(t, i), m.C(t, j)));
  double sum = 0;
  for (const auto& [a, b] : edges) sum += (m.V.row(a) - m.V.row(b)).norm();
  return sum / static_cast<double>(edges.size());
}

TEST(Tetrahedralize, BoxVolumeOrientationAndLabels) {
  const SurfaceMesh s = box(20, 12, 8);
  TetrahedralizeOptions opt;
  opt.target_edge_length = 2.0;
  const TetrahedralizeResult r = tetrahedralize(s, opt);
  expect_no_process_left();
  ASSERT_TRUE(r.mesh.is_tet_mesh());
  EXPECT_NEAR(total_volume_all_positive(r.mesh), 20.0 * 12 * 8, 1e-9 * 20 * 12 * 8);

  // Each boundary triangle carries the label of the box face it lies on and points out of the box.
  const Eigen::Vector3d lo(0, 0, 0), hi(20, 12, 8);
  ASSERT_EQ(r.boundary_faces.rows(), r.boundary_labels.size());
  ASSERT_GT(r.boundary_faces.rows(), 12);
  double area = 0;
  for (int f = 0; f < r.boundary_faces.rows(); ++f) {
    const int label = r.boundary_labels(f);
    ASSERT_GE(label, 1);
    ASSERT_LE(label, 6);
    const int axis = (label - 1) / 2;
    const bool high = (label - 1) % 2 == 1;
    const Eigen::Vector3d a = r.mesh.V.row(r.boundary_faces(f, 0)), b = r.mesh.V.row(r.boundary_faces(f, 1)),
                          c = r.mesh.V.row(r.boundary_faces(f, 2));
    const double plane = high ? hi(axis) : lo(axis);
    for (const Eigen::Vector3d& p : {a, b, c}) EXPECT_NEAR(p(axis), plane, 1e-9) << "face " << f;
    const Eigen::Vector3d n = (b - a).cross(c - a);
    EXPECT_GT(high ? n(axis) : -n(axis), 0) << "face " << f << " points inward";
    area += n.norm() / 2;
  }
  EXPECT_NEAR(area, 2 * (20.0 * 12 + 20 * 8 + 12 * 8), 1e-9 * 1000);

  const double mean = mean_edge_length(r.mesh);
  EXPECT_GT(mean, opt.target_edge_length / 1.5);
  EXPECT_LT(mean, opt.target_edge_length * 1.5);
}

TEST(Tetrahedralize, IcosphereFillsItsPolyhedron) {
  const SurfaceMesh s = icosphere(10, 2);
  TetrahedralizeOptions opt;
  opt.target_edge_length = 2.0;
  const TetrahedralizeResult r = tetrahedralize(s, opt);
  const double expected = enclosed_volume(s);
  EXPECT_NEAR(total_volume_all_positive(r.mesh), expected, 1e-9 * expected);
  EXPECT_EQ(r.boundary_labels.size(), r.boundary_faces.rows());
  for (int f = 0; f < r.boundary_labels.size(); ++f) EXPECT_EQ(r.boundary_labels(f), 0);
  const double mean = mean_edge_length(r.mesh);
  EXPECT_GT(mean, opt.target_edge_length / 1.5);
  EXPECT_LT(mean, opt.target_edge_length * 1.5);
}

TEST(Tetrahedralize, TheEdgeLengthForATetCountInvertsThePrediction) {
  const SurfaceMesh s = icosphere(10, 2);
  TetrahedralizeOptions opt;
  const double volume = enclosed_volume(s);
  EXPECT_NEAR(volume, 4.0 / 3.0 * M_PI * 1000, 0.05 * 4.0 / 3.0 * M_PI * 1000);  // a sphere of radius 10, nearly
  for (const double edge : {0.7, 2.0, 3.5}) {
    opt.target_edge_length = edge;
    EXPECT_NEAR(edge_length_for_tet_count(volume, predicted_tet_count(volume, opt), opt), edge, 1e-12);
  }
  // Eight times the tets: half the edge.
  opt.target_edge_length = 2.0;
  EXPECT_NEAR(edge_length_for_tet_count(volume, 8 * predicted_tet_count(volume, opt), opt), 1.0, 1e-12);
}

TEST(Tetrahedralize, PreserveSurfaceKeepsTheInputBoundary) {
  const SurfaceMesh s = icosphere(10, 2);
  TetrahedralizeOptions opt;
  opt.preserve_surface = true;
  const TetrahedralizeResult r = tetrahedralize(s, opt);
  EXPECT_EQ(r.boundary_faces.rows(), s.F.rows());
  EXPECT_NEAR(total_volume_all_positive(r.mesh), enclosed_volume(s), 1e-9 * enclosed_volume(s));
}

void expect_tetgen_error(const SurfaceMesh& s, const std::string& words) {
  try {
    tetrahedralize(s);
    FAIL() << "expected facehex::Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.subject(), "tetgen");
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(Tetrahedralize, RejectsAnOpenSurface) {
  SurfaceMesh s = box(1, 1, 1);
  s.F.conservativeResize(10, 3);  // drop the +z face
  s.labels.conservativeResize(10);
  expect_tetgen_error(s, "not closed");
}

TEST(Tetrahedralize, RejectsInconsistentOrientation) {
  SurfaceMesh s = box(1, 1, 1);
  std::swap(s.F(0, 1), s.F(0, 2));
  expect_tetgen_error(s, "oriented");
}

TEST(Tetrahedralize, RejectsASelfIntersectingSurface) {
  // Two closed boxes overlapping each other, given as one surface.
  const SurfaceMesh a = box(2, 2, 2);
  SurfaceMesh s;
  s.V.resize(16, 3);
  s.V.topRows(8) = a.V;
  s.V.bottomRows(8) = a.V.rowwise() + Eigen::RowVector3d(1.0, 0.7, 0.6);
  s.F.resize(24, 3);
  s.F.topRows(12) = a.F;
  s.F.bottomRows(12) = a.F.array() + 8;
  expect_tetgen_error(s, "intersects itself");
  EXPECT_THROW(tetrahedralize(s), SelfIntersectingSurface);  // its own type: the segmentation remeshes and retries
  expect_no_process_left();  // the quality mesh, started beside the check, was stopped and reaped
}

TEST(Tetrahedralize, RejectsBadLabelCount) {
  SurfaceMesh s = box(1, 1, 1);
  s.labels.conservativeResize(5);
  expect_tetgen_error(s, "labels");
}

// The prediction is within a factor of two of what TetGen makes, and a surface over the budget is refused before
// TetGen starts, with the estimate and the option that changes it.
TEST(Tetrahedralize, ATetCountOverTheBudgetIsRefusedUpFront) {
  const SurfaceMesh s = box(40, 30, 20);
  TetrahedralizeOptions opt;
  opt.target_edge_length = 2.0;
  const double predicted = predicted_tet_count(40.0 * 30 * 20, opt);
  const int made = tetrahedralize(s, opt).mesh.num_cells();
  EXPECT_GT(predicted, made / 2.0);
  EXPECT_LT(predicted, made * 2.0);
  EXPECT_GT(max_tets_for_memory(), 1e5);

  opt.max_tets = predicted / 2;
  try {
    tetrahedralize(s, opt);
    FAIL() << "over the budget, yet meshed";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("at an edge length of 2 mm the model would have about"), std::string::npos) << m;
    EXPECT_NE(m.find("raise --edge-length"), std::string::npos) << m;
  }
  opt.target_edge_length = 0.02;  // a typo of 2: refused by the machine's own budget
  opt.max_tets = 0;
  EXPECT_THROW(tetrahedralize(s, opt), Error);
  expect_no_process_left();
}

}  // namespace
}  // namespace facehex
