#include "core/shape/untangle.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <utility>

#include "core/mesh/corner_jacobian.h"
#include "core/util/error.h"
#include "tests/core/test_meshes.h"

namespace facehex {
namespace {

std::vector<char> boundary_fixed(const VolumeMesh& m) {
  const Eigen::MatrixXd& mask = m.point_data.at(kSideMaskArray);
  std::vector<char> fixed(m.num_vertices());
  for (int v = 0; v < m.num_vertices(); ++v) fixed[v] = mask(v) != 0;
  return fixed;
}

// Untangles or relaxes `m` with its boundary held (each vertex moves in space, the sides' vertices not at all).
UntangleReport untangle_with_fixed_boundary(VolumeMesh& m, const UntangleOptions& options = {}) {
  VertexPlacement placement = spatial_placement(m.V, boundary_fixed(m));
  return untangle(m, placement, options);
}

// The whole mesh's relaxation towards the shapes of `target`, at most `max_sweeps` sweeps.
UntangleOptions relaxation_towards(const VolumeMesh& target, int max_sweeps) {
  UntangleOptions relax;
  relax.target = &target;
  relax.whole_mesh = true;
  relax.max_sweeps = max_sweeps;
  return relax;
}

TEST(Untangle, RepairsADeliberatelyInvertedMeshWithoutMovingTheBoundary) {
  VolumeMesh m = test::hex_box(4, 4, 4, 4, 4, 4);
  const Eigen::MatrixXd boundary_before = m.V;
  // Push the interior vertex at (2,2,2) through two cells and drag a neighbour the other way.
  const int centre = (2 * 5 + 2) * 5 + 2, neighbour = (2 * 5 + 2) * 5 + 3;
  m.V.row(centre) += Eigen::RowVector3d(1.6, 0.3, -0.2);
  m.V.row(neighbour) += Eigen::RowVector3d(-1.5, 0.0, 0.4);
  const int inverted_before = static_cast<int>(check_corner_jacobians(m).inverted.size());
  ASSERT_GT(inverted_before, 0);
  const std::vector<char> fixed = boundary_fixed(m);
  VertexPlacement placement = spatial_placement(m.V, fixed);
  const UntangleReport r = untangle(m, placement);
  EXPECT_EQ(r.inverted_before, inverted_before);
  EXPECT_EQ(r.inverted_after, 0);
  EXPECT_TRUE(check_corner_jacobians(m).inverted.empty());
  EXPECT_GT(r.min_scaled_jacobian_after, 0.2);
  EXPECT_EQ(r.stalled_passes, 0);
  for (int v = 0; v < m.num_vertices(); ++v)
    if (fixed[v]) {
      EXPECT_EQ((m.V.row(v) - boundary_before.row(v)).norm(), 0.0) << v;
    }
}

// A box of n x n x n unit hexes whose interior vertex (1,1,1) is pushed through the corner cell's far corner (0,0,0)
// and held there, with the boundary: a fold no free vertex can reach. Its placement moves the others in space.
struct HeldFold {
  VolumeMesh mesh;
  VertexPlacement placement;
};
HeldFold held_fold(int n) {
  VolumeMesh m = test::hex_box(n, n, n, n, n, n);
  const int held = (n + 2) * (n + 1) + 1;  // vertex (1,1,1)
  m.V.row(held) << -0.5, -0.4, -0.3;
  std::vector<char> fixed = boundary_fixed(m);
  fixed[held] = 1;
  VertexPlacement placement = spatial_placement(m.V, fixed);
  return {std::move(m), std::move(placement)};
}

// The held fold: the repair stops once its unusable cells have stopped becoming fewer, reports the pass as stalled and
// says what is left, instead of sweeping to its limit.
TEST(Untangle, AFoldNoVertexCanUntangleStopsThePassAndIsReported) {
  HeldFold fold = held_fold(4);
  ASSERT_FALSE(check_corner_jacobians(fold.mesh).inverted.empty());
  UntangleOptions options;
  options.max_sweeps = 500;
  const UntangleReport r = untangle(fold.mesh, fold.placement, options);
  EXPECT_GT(r.inverted_after, 0);
  EXPECT_EQ(r.stalled_passes, 1);
  EXPECT_LT(r.sweeps, 50);
  EXPECT_GT(r.free_vertices, 0);  // there were vertices to move: they could not help
}

// The same held fold with every vertex of a large box free: a stalled pass over thousands of vertices gives up after
// fewer sweeps (its patience is counted in vertex steps), one over a few dozen after more.
TEST(Untangle, AStalledPassOverManyVerticesGivesUpSooner) {
  auto stalled_sweeps = [](int n, int rings) {
    HeldFold fold = held_fold(n);
    UntangleOptions options;
    options.max_sweeps = 500;
    options.rings = rings;
    const UntangleReport r = untangle(fold.mesh, fold.placement, options);
    EXPECT_EQ(r.stalled_passes, 1) << n;
    EXPECT_GT(r.inverted_after, 0) << n;
    return std::make_pair(r.sweeps, r.free_vertices);
  };
  const auto [few_sweeps, few] = stalled_sweeps(4, 2);
  const auto [many_sweeps, many] = stalled_sweeps(20, 40);
  ASSERT_LT(few, 100);
  ASSERT_GT(many, 5000);
  EXPECT_LE(many_sweeps, 8);
  EXPECT_GE(few_sweeps, 15);
}

TEST(Untangle, RepairsAFlatCellThatIsNotInverted) {
  VolumeMesh m = test::hex_box(3, 3, 3, 3, 3, 3);
  // Interior vertex (1,1,1) moved almost onto the midpoint of two of its neighbours: positive but ~0 Jacobians.
  auto id = [](int i, int j, int k) { return (k * 4 + j) * 4 + i; };
  const double t = 1 - 1e-9;
  m.V.row(id(1, 1, 1)) = (1 - t) * m.V.row(id(1, 1, 1)) + t * 0.5 * (m.V.row(id(2, 1, 1)) + m.V.row(id(1, 2, 1)));
  const CornerJacobianCheck before = check_corner_jacobians(m);
  ASSERT_TRUE(before.inverted.empty());
  ASSERT_FALSE(before.degenerate.empty());
  const UntangleReport r = untangle_with_fixed_boundary(m);
  EXPECT_EQ(r.degenerate_before, static_cast<int>(before.degenerate.size()));
  EXPECT_EQ(r.degenerate_after, 0);
  EXPECT_EQ(r.inverted_after, 0);
  EXPECT_TRUE(check_corner_jacobians(m).unusable().empty());
  EXPECT_GT(r.min_scaled_jacobian_after, 0.2);
}

TEST(Untangle, LeavesAGoodMeshUntouched) {
  VolumeMesh m = test::hex_box(3, 3, 3);
  test::jitter_interior(m, 0.05);
  const Eigen::MatrixXd before = m.V;
  const UntangleReport r = untangle_with_fixed_boundary(m);
  EXPECT_EQ(r.bad_before, 0);
  EXPECT_EQ(m.V, before);
}

// A poorly shaped cell (a squeezed interior vertex) is bad on its own, but not when the mesh it was mapped from had
// it as poor: then it is kept as it is.
TEST(Untangle, KeepsCellsAsPoorAsInTheReference) {
  VolumeMesh m = test::hex_box(3, 3, 3, 3, 3, 3);
  auto id = [](int i, int j, int k) { return (k * 4 + j) * 4 + i; };
  m.V.row(id(1, 1, 1)) += Eigen::RowVector3d(0.3, 0.3, 0.3);  // one corner of a cell at scaled Jacobian 0.18
  ASSERT_TRUE(check_corner_jacobians(m).unusable().empty());
  Eigen::VectorXd reference(m.num_cells());
  for (int c = 0; c < m.num_cells(); ++c) reference(c) = scaled_jacobian(m.types[c], cell_nodes(m, c));
  ASSERT_LT(reference.minCoeff(), 0.2);

  UntangleOptions as_reference;
  as_reference.reference_scaled_jacobian = reference;
  VolumeMesh kept = m;
  const UntangleReport r = untangle_with_fixed_boundary(kept, as_reference);
  EXPECT_EQ(r.bad_before, 0);
  EXPECT_EQ(kept.V, m.V);

  VolumeMesh improved = m;  // without the reference the same cells are bad and are improved
  const UntangleReport r2 = untangle_with_fixed_boundary(improved);
  EXPECT_GT(r2.bad_before, 0);
  EXPECT_GT(r2.min_scaled_jacobian_after, r2.min_scaled_jacobian_before);

  UntangleOptions wrong_size;
  wrong_size.reference_scaled_jacobian = Eigen::VectorXd::Ones(3);
  EXPECT_THROW(untangle_with_fixed_boundary(improved, wrong_size), Error);
}

// A finishing pass grows its region from the unusable cells only: a merely poor cell far from them is left alone.
TEST(Untangle, FinishingPassMovesOnlyAroundUnusableCells) {
  VolumeMesh m = test::hex_box(8, 3, 3, 8, 3, 3);
  auto id = [](int i, int j, int k) { return (k * 4 + j) * 9 + i; };
  m.V.row(id(1, 1, 1)) += Eigen::RowVector3d(1.6, 0.3, -0.2);  // inverts cells at the -x end
  m.V.row(id(7, 1, 1)) += Eigen::RowVector3d(0.3, 0.3, 0.3);   // only squeezes a cell at the +x end
  const VolumeMesh start = m;
  const int squeezed = (1 * 3 + 1) * 8 + 7;  // the cell whose first corner is the vertex (7, 1, 1)
  ASSERT_LT(scaled_jacobian(m.types[squeezed], cell_nodes(m, squeezed)), 0.2);
  const std::vector<int> unusable = check_corner_jacobians(m).unusable();
  ASSERT_EQ(std::count(unusable.begin(), unusable.end(), squeezed), 0);
  UntangleOptions finishing;
  finishing.seed_unusable_only = true;
  finishing.rings = 1;
  const UntangleReport r = untangle_with_fixed_boundary(m, finishing);
  EXPECT_GT(r.inverted_before, 0);
  EXPECT_EQ(r.inverted_after, 0);
  EXPECT_EQ(m.V.row(id(7, 1, 1)), start.V.row(id(7, 1, 1)));  // the squeezed vertex did not move
  EXPECT_NE(m.V.row(id(1, 1, 1)), start.V.row(id(1, 1, 1)));
}

// Relaxes the whole of m (boundary fixed) towards the shapes of target, blended towards_ideal (UntangleOptions).
void relax_towards(VolumeMesh& m, const VolumeMesh& target, double towards_ideal) {
  UntangleOptions relax;
  relax.target = &target;
  relax.target_towards_ideal = towards_ideal;
  relax.whole_mesh = true;
  untangle_with_fixed_boundary(m, relax);
}

// Shape relaxation with a target (the standard a mesh was mapped from): the target's own shape is where it settles.
TEST(ShapeRelaxation, ReturnsAPerturbedMeshToItsTargetShape) {
  VolumeMesh target = test::hex_box(4, 4, 4, 4, 4, 4);
  test::jitter_interior(target, 0.25);  // a target that is not the ideal cube grid
  VolumeMesh m = target;
  test::jitter_interior(m, 0.2, 11);  // the "mapping" moved the interior
  const double start = (m.V - target.V).cwiseAbs().maxCoeff();
  ASSERT_GT(start, 0.1);
  UntangleOptions relax = relaxation_towards(target, 200);
  VolumeMesh moved = m;
  const UntangleReport r = untangle_with_fixed_boundary(moved, relax);
  EXPECT_EQ(r.free_vertices, 27);  // every interior vertex, though no cell is bad
  // Sweeps stop once no vertex moves more than 1e-3 of its edge length (4 mm here): the target within that.
  EXPECT_LT((moved.V - target.V).cwiseAbs().maxCoeff(), 1e-3 * 4);
  // Without the target, the same steps aim at cubes: the jittered target is not where they settle.
  VolumeMesh ideal = target;
  test::jitter_interior(ideal, 0.2, 11);
  UntangleOptions cubes = relax;
  cubes.target = nullptr;
  untangle_with_fixed_boundary(ideal, cubes);
  EXPECT_GT((ideal.V - target.V).cwiseAbs().maxCoeff(), 0.1);
}

// A tether to the start trades the target's shape for staying put, by its weight: the heavier, the less the
// vertices move and the farther they stay from the target's shape; weight 0 is no tether at all; a tether at the
// target's own positions does not keep the mesh from reaching it.
TEST(ShapeRelaxation, ATetherTradesTheTargetsShapeForStayingWhereTheMappingPutTheVertices) {
  VolumeMesh target = test::hex_box(4, 4, 4, 4, 4, 4);
  test::jitter_interior(target, 0.25);
  VolumeMesh start = target;
  test::jitter_interior(start, 0.2, 11);
  UntangleOptions relax = relaxation_towards(target, 200);
  const auto relaxed = [&](const UntangleOptions& o) {
    VolumeMesh moved = start;
    untangle_with_fixed_boundary(moved, o);
    return moved.V;
  };
  const auto mean_distance = [](const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
    return (a - b).rowwise().norm().mean();
  };
  const Eigen::MatrixXd free = relaxed(relax);
  double last_moved = 1e9, last_off_target = -1;
  for (const double weight : {0.0, 0.2, 2.0, 20.0, 1000.0}) {
    UntangleOptions tethered = relax;
    tethered.tether = start.V;
    tethered.tether_weight = weight;
    const Eigen::MatrixXd V = relaxed(tethered);
    if (weight == 0) {
      EXPECT_EQ(V, free);
    }
    const double moved = mean_distance(V, start.V), off_target = mean_distance(V, target.V);
    EXPECT_LT(moved, last_moved) << "weight " << weight;
    EXPECT_GT(off_target, last_off_target) << "weight " << weight;
    last_moved = moved;
    last_off_target = off_target;
  }
  EXPECT_LT(last_moved, 0.1 * mean_distance(free, start.V));
  UntangleOptions at_target = relax;
  at_target.tether = target.V;
  at_target.tether_weight = 2;
  EXPECT_LT((relaxed(at_target) - target.V).cwiseAbs().maxCoeff(), 1e-3 * 4);
}

// A relaxation told to stop once its sweeps lower the energy by little stops before the sweeps that only creep on,
// near where they would have taken the mesh; with the share 0 it sweeps until the vertices stop moving.
TEST(ShapeRelaxation, StopsOnceASweepLowersTheEnergyByLittle) {
  VolumeMesh target = test::hex_box(6, 6, 6, 6, 6, 6);
  test::jitter_interior(target, 0.25);
  VolumeMesh start = target;
  test::jitter_interior(start, 0.3, 11);
  const auto mean_off_target = [&](const VolumeMesh& m) { return (m.V - target.V).rowwise().norm().mean(); };
  UntangleOptions relax = relaxation_towards(target, 200);
  VolumeMesh full = start;
  const UntangleReport until_still = untangle_with_fixed_boundary(full, relax);
  relax.settled_energy_share = 1e-2;
  VolumeMesh settled = start;
  const UntangleReport until_settled = untangle_with_fixed_boundary(settled, relax);
  EXPECT_TRUE(until_settled.settled);
  EXPECT_FALSE(until_still.settled);
  EXPECT_LT(until_settled.sweeps, until_still.sweeps / 2);
  EXPECT_GT(until_settled.sweeps, 2);
  EXPECT_LT(mean_off_target(settled), 0.2 * mean_off_target(start));
  EXPECT_GT(mean_off_target(settled), mean_off_target(full));
}

// A relaxation that stops when settled also lets rest the vertices whose steps took off less than their share of a
// settled sweep's decrease: where the mesh is already nearly at its target the sweeps soon pass it by, while where it
// is far from it they go on until the relaxation settles.
TEST(ShapeRelaxation, LetsTheVerticesRestWhoseStepsHardlyLowerTheEnergy) {
  VolumeMesh target = test::hex_box(24, 6, 6, 24, 6, 6);
  test::jitter_interior(target, 0.25);
  VolumeMesh far = target, near = target;
  test::jitter_interior(far, 0.3, 11);
  test::jitter_interior(near, 0.001, 13);
  VolumeMesh start = near;
  std::vector<int> moved_far;  // the quarter at x < 6 far from its target, the rest nearly at it
  for (int v = 0; v < start.num_vertices(); ++v)
    if (target.V(v, 0) < 6 && far.V.row(v) != target.V.row(v)) {
      start.V.row(v) = far.V.row(v);
      moved_far.push_back(v);
    }
  const auto mean_off_target = [&](const VolumeMesh& m, const std::vector<int>& vertices) {
    double sum = 0;
    for (int v : vertices) sum += (m.V.row(v) - target.V.row(v)).norm();
    return sum / vertices.size();
  };
  UntangleOptions relax = relaxation_towards(target, 200);
  relax.settled_energy_share = 1e-3;
  VolumeMesh m = start;
  const UntangleReport r = untangle_with_fixed_boundary(m, relax);
  EXPECT_TRUE(r.settled);
  EXPECT_EQ(r.free_vertices, 23 * 5 * 5);
  EXPECT_LT(r.vertex_steps, 0.5 * r.sweeps * r.free_vertices);
  EXPECT_LT(mean_off_target(m, moved_far), 0.2 * mean_off_target(start, moved_far));
}

TEST(ShapeRelaxation, GivesTheSameMeshOnOneThreadAndOnTwo) {
  // Long in x, so that the free vertices are cut into several slabs that step in parallel.
  VolumeMesh target = test::hex_box(16, 6, 6, 16, 6, 6);
  test::jitter_interior(target, 0.2);
  VolumeMesh start = target;
  test::jitter_interior(start, 0.3, 5);
  UntangleOptions relax = relaxation_towards(target, 20);
  // Also when the sweeps stop on their energy: each sweep's decrease is summed in the same order on any thread count.
  for (const double settled_share : {0.0, 1e-2}) {
    relax.settled_energy_share = settled_share;
    std::vector<Eigen::MatrixXd> results;
    std::vector<int> sweeps;
    for (const int threads : {1, 2}) {
      VolumeMesh moved = start;
      relax.threads = threads;
      sweeps.push_back(untangle_with_fixed_boundary(moved, relax).sweeps);
      results.push_back(moved.V);
    }
    EXPECT_GT((results[0] - start.V).cwiseAbs().maxCoeff(), 0.05);
    EXPECT_EQ((results[0] - results[1]).cwiseAbs().maxCoeff(), 0.0) << settled_share;
    EXPECT_EQ(sweeps[0], sweeps[1]) << settled_share;
  }
}

TEST(ShapeRelaxation, ReportsEachSweepAndCanBeCancelledBetweenSweeps) {
  VolumeMesh target = test::hex_box(4, 4, 4, 4, 4, 4);
  VolumeMesh m = target;
  test::jitter_interior(m, 0.2, 11);
  UntangleOptions relax = relaxation_towards(target, 40);
  std::vector<double> fractions;
  relax.progress = [&](const std::string& stage, double f) {
    EXPECT_EQ(stage, "untangling");
    fractions.push_back(f);
    return true;
  };
  VolumeMesh moved = m;
  const UntangleReport r = untangle_with_fixed_boundary(moved, relax);
  ASSERT_EQ(static_cast<int>(fractions.size()), r.sweeps);  // one report per sweep made
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_DOUBLE_EQ(fractions.front(), 1.0 / relax.max_sweeps);
  EXPECT_LE(fractions.back(), 1.0);

  // Cancelled after the third sweep: the exception comes out, the mesh is whole (a sweep is never cut short).
  int calls = 0;
  relax.progress = [&](const std::string&, double) { return ++calls < 3; };
  VolumeMesh cancelled = m;
  EXPECT_THROW(untangle_with_fixed_boundary(cancelled, relax), Cancelled);
  EXPECT_EQ(calls, 3);
  EXPECT_TRUE(check_corner_jacobians(cancelled).inverted.empty());
  EXPECT_GT((cancelled.V - m.V).cwiseAbs().maxCoeff(), 0) << "three sweeps moved nothing";
}

// A mesh that already has its target's shape does not move, whatever the pull towards ideal cells (which acts only
// in proportion to a corner's distortion): mapping a standard onto itself stays the identity.
TEST(ShapeRelaxation, LeavesAMeshWithTheTargetShapeInPlace) {
  VolumeMesh target = test::hex_box(4, 3, 5, 4, 3, 5);
  test::jitter_interior(target, 0.3);
  for (const double towards_ideal : {0.0, 0.5, 1.0}) {
    VolumeMesh m = target;
    m.V *= 2.5;  // size does not matter, only shape
    const Eigen::MatrixXd start = m.V;
    relax_towards(m, target, towards_ideal);
    EXPECT_LT((m.V - start).cwiseAbs().maxCoeff(), 1e-9) << towards_ideal;
  }
}

// The pull towards ideal cells: a mesh of cubes relaxed towards a poor target (a jittered grid) goes back to the
// target's poor cells with target_towards_ideal = 0 and keeps better cells with 1.
TEST(ShapeRelaxation, TowardsIdealImprovesCellsOfADistortedMesh) {
  VolumeMesh target = test::hex_box(4, 4, 4, 4, 4, 4);
  test::jitter_interior(target, 0.35);
  const VolumeMesh cubes = test::hex_box(4, 4, 4, 4, 4, 4);
  auto mean_scaled_jacobian = [](const VolumeMesh& mesh) {
    double sum = 0;
    for (int c = 0; c < mesh.num_cells(); ++c) sum += scaled_jacobian(mesh.types[c], cell_nodes(mesh, c));
    return sum / mesh.num_cells();
  };
  std::vector<double> quality;
  for (const double towards_ideal : {0.0, 1.0}) {
    VolumeMesh m = cubes;
    relax_towards(m, target, towards_ideal);
    quality.push_back(mean_scaled_jacobian(m));
  }
  EXPECT_GT(quality[1], quality[0] + 0.02);
  EXPECT_LT(quality[0], mean_scaled_jacobian(target) + 0.01);  // 0: the target's own cells, about
}

TEST(ShapeRelaxation, RejectsATargetWithOtherCells) {
  VolumeMesh m = test::hex_box(2, 2, 2, 2, 2, 2);
  const VolumeMesh other = test::hex_box(3, 2, 2, 3, 2, 2);
  UntangleOptions relax;
  relax.target = &other;
  relax.whole_mesh = true;
  EXPECT_THROW(untangle_with_fixed_boundary(m, relax), Error);
}

// Vertices on a curved surface move through surface parameters (a placement, vertex_placement.h): however far the
// relaxation slides them, they stay exactly on it.
TEST(ShapeRelaxation, SlidesBoundaryVerticesAlongAnAnalyticSurface) {
  const int n = 4;
  VolumeMesh target = test::hex_box(n, n, n, n, n, n);
  auto height = [n](double x, double y) { return n + 0.15 * (x - 2) * (x - 2) - 0.1 * (y - 1) * (y - 2); };
  auto on_top = [n](const Eigen::RowVector3d& x) { return x.z() > n - 0.5; };
  for (int v = 0; v < target.num_vertices(); ++v)
    if (on_top(target.V.row(v))) target.V(v, 2) = height(target.V(v, 0), target.V(v, 1));
  VolumeMesh m = target;
  std::vector<char> fixed = boundary_fixed(m), top(m.num_vertices(), 0);
  // The top's vertices, but for its rim, are shifted along the surface; the interior is jittered.
  test::jitter_interior(m, 0.2, 3);
  for (int v = 0; v < m.num_vertices(); ++v) {
    const Eigen::RowVector3d x = m.V.row(v);
    if (!on_top(x) || x.x() < 0.5 || x.x() > n - 0.5 || x.y() < 0.5 || x.y() > n - 0.5) continue;
    top[v] = 1;
    fixed[v] = 0;
    m.V(v, 0) += 0.3 * std::sin(3.0 * v);
    m.V(v, 1) += 0.3 * std::cos(5.0 * v);
    m.V(v, 2) = height(m.V(v, 0), m.V(v, 1));
  }
  VertexPlacement placement = spatial_placement(m.V, fixed);
  for (int v = 0; v < m.num_vertices(); ++v)
    if (top[v]) placement.movable[v] = Eigen::Vector3d(1, 1, 0).asDiagonal();  // (x, y) move, z follows
  placement.place = [&](int v, const Eigen::Vector3d& q, Eigen::Vector3d& x, Eigen::Matrix3d& dxdq) {
    x = q;
    dxdq.setIdentity();
    if (top[v]) {
      x.z() = height(q.x(), q.y());
      dxdq.row(2) << 0.3 * (q.x() - 2), -0.1 * (2 * q.y() - 3), 0;
    }
    return true;
  };
  const Eigen::MatrixXd start = m.V;
  UntangleOptions relax = relaxation_towards(target, 100);
  untangle(m, placement, relax);
  double slid = 0;
  for (int v = 0; v < m.num_vertices(); ++v) {
    if (!top[v]) continue;
    EXPECT_NEAR(m.V(v, 2), height(m.V(v, 0), m.V(v, 1)), 1e-9) << v;
    slid = std::max(slid, (m.V.row(v) - start.row(v)).norm());
  }
  EXPECT_GT(slid, 0.1);  // they did move: back towards the target's places along the surface
  EXPECT_LT((m.V - target.V).cwiseAbs().maxCoeff(), 0.05);
  for (int v = 0; v < m.num_vertices(); ++v)
    if (fixed[v]) {
      EXPECT_EQ(m.V.row(v), start.row(v)) << "held vertex " << v << " moved";
    }
}

// The steps' guard against poorer cells, tempted: cubes relaxed towards a strongly sheared target (its cells' scaled
// Jacobian about 0.37) with only the bottom face held would shear all the way; with keep_above no cell at or above
// it ends below it, and no cell becomes unusable.
TEST(Untangle, NoStepDropsAGoodCellBelowItsFloorHoweverTheEnergyPulls) {
  const VolumeMesh cubes = test::hex_box(3, 3, 3, 3, 3, 3);
  VolumeMesh target = cubes;
  target.V.col(0) += 2.5 * target.V.col(2);
  std::vector<char> bottom(cubes.num_vertices());
  for (int v = 0; v < cubes.num_vertices(); ++v) bottom[v] = cubes.V(v, 2) < 0.5;
  auto lowest_scaled_jacobian = [](const VolumeMesh& m) {
    double lowest = 1;
    for (int c = 0; c < m.num_cells(); ++c) lowest = std::min(lowest, scaled_jacobian(m.types[c], cell_nodes(m, c)));
    return lowest;
  };
  ASSERT_LT(lowest_scaled_jacobian(target), 0.4);
  for (const double floor : {0.0, 0.6}) {
    VolumeMesh m = cubes;
    UntangleOptions relax;
    relax.target = &target;
    relax.whole_mesh = true;
    relax.keep_above = floor;
    relax.max_sweeps = 100;
    VertexPlacement placement = spatial_placement(m.V, bottom);
    untangle(m, placement, relax);
    EXPECT_TRUE(check_corner_jacobians(m).unusable().empty());
    if (floor == 0) {
      EXPECT_LT(lowest_scaled_jacobian(m), 0.45);  // unguarded, the energy takes the cells to the target's shear
    } else {
      EXPECT_GE(lowest_scaled_jacobian(m), floor);
      EXPECT_GT((m.V - cubes.V).cwiseAbs().maxCoeff(), 0.1);  // sheared as far as the floor allows
    }
  }
}

}  // namespace
}  // namespace facehex
