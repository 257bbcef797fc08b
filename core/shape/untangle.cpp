#include "core/shape/untangle.h"

#include <omp.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "core/mesh/corner_jacobian.h"
#include "core/shape/cell_bounds.h"
#include "core/shape/corner_energy.h"
#include "core/util/idle_cores.h"

namespace facehex {
namespace {

struct Corner {
  int cell, k;  // k: corner index, or kSample + s for the cell's interior sample s (corner_jacobian.h)
};
constexpr int kSample = kSampleSlot;
constexpr double kNearlyInverted = 0.1;  // normalized corner determinant below which a vertex is always revisited

// Vertices that share no cell can step at the same time: a step reads and writes only the cells around its vertex.
// The free vertices are cut, by their rank along the region's longest extent, into slabs whose cells reach at most
// into the neighbouring slab; the even slabs then step in parallel, then the odd ones. That is two waits per sweep
// whatever the thread count, so a thread that loses its core to another job delays a sweep once, rather than at each
// of the dozens of colour classes a graph colouring needs. The slabs depend on the mesh only: the result does not
// depend on the thread count. Fewer, thicker slabs where thin ones would share cells; one slab for a small region.
std::vector<std::vector<int>> cut_into_slabs(const VolumeMesh& mesh, const std::vector<std::vector<int>>& cells_of,
                                             const std::vector<int>& free_vertices) {
  constexpr int kMostSlabs = 16, kLeastSlabVertices = 64;
  const int n = static_cast<int>(free_vertices.size());
  if (n == 0) return {};
  Eigen::MatrixXd X(n, 3);
  for (int i = 0; i < n; ++i) X.row(i) = mesh.V.row(free_vertices[i]);
  int axis = 0;
  (X.colwise().maxCoeff() - X.colwise().minCoeff()).maxCoeff(&axis);
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return X(a, axis) < X(b, axis); });
  std::vector<int> slab_of(mesh.num_vertices(), -1);
  for (int slabs = std::min(kMostSlabs, n / kLeastSlabVertices); slabs >= 2; --slabs) {
    for (int rank = 0; rank < n; ++rank)
      slab_of[free_vertices[order[rank]]] = static_cast<int>(static_cast<long long>(rank) * slabs / n);
    bool thick_enough = true;
    for (int i = 0; i < n && thick_enough; ++i)
      for (int c : cells_of[free_vertices[i]]) {
        int lowest = slabs, highest = -1;
        for (int local = 0; local < node_count(mesh.types[c]); ++local) {
          const int slab = slab_of[mesh.C(c, local)];
          if (slab < 0) continue;  // not free: never moves
          lowest = std::min(lowest, slab);
          highest = std::max(highest, slab);
        }
        if (highest - lowest > 1) {
          thick_enough = false;
          break;
        }
      }
    if (!thick_enough) continue;
    std::vector<std::vector<int>> cut(slabs);
    for (int v : free_vertices) cut[slab_of[v]].push_back(v);
    return cut;
  }
  return {free_vertices};
}

}  // namespace

UntangleReport untangle(VolumeMesh& mesh, VertexPlacement& placement, const UntangleOptions& options) {
  const std::vector<Eigen::Matrix3d>& movable = placement.movable;
  UntangleReport report;
  const int nc = mesh.num_cells(), nv = mesh.num_vertices();
  const CellBounds bounds(mesh, options);
  auto is_bad = [&](int c) { return bounds.is_bad(mesh, c); };
  auto unusable = [&](int c) { return is_unusable(mesh.types[c], cell_nodes(mesh, c)); };
  auto tally = [&](int& inverted, int& degenerate, int& bad, double& min_sj) {
    const CellBounds::Counts counts = bounds.count(mesh);
    inverted = counts.inverted;
    degenerate = counts.degenerate;
    bad = counts.bad;
    min_sj = counts.min_scaled_jacobian;
  };
  tally(report.inverted_before, report.degenerate_before, report.bad_before, report.min_scaled_jacobian_before);
  if (report.bad_before == 0 && !options.whole_mesh) {
    report.inverted_after = report.inverted_before;
    report.degenerate_after = report.degenerate_before;
    report.min_scaled_jacobian_after = report.min_scaled_jacobian_before;
    return report;
  }

  // Vertex -> cells, and the free vertices within `rings` rings of a bad cell.
  std::vector<std::vector<int>> cells_of(nv);
  for (int c = 0; c < nc; ++c)
    for (int i = 0; i < node_count(mesh.types[c]); ++i) cells_of[mesh.C(c, i)].push_back(c);
  std::vector<char> region(nv, 1);
  if (!options.whole_mesh) {
    std::vector<char> in_bad_cell(nv, 0);
    for (int c = 0; c < nc; ++c)
      if (options.seed_unusable_only ? unusable(c) : is_bad(c))
        for (int i = 0; i < node_count(mesh.types[c]); ++i) in_bad_cell[mesh.C(c, i)] = 1;
    region = within_cell_rings(mesh, std::move(in_bad_cell), options.rings);
  }
  std::vector<int> free_vertices;
  for (int v = 0; v < nv; ++v)
    if (region[v] && !movable[v].isZero()) free_vertices.push_back(v);
  report.free_vertices = static_cast<int>(free_vertices.size());
  const std::vector<std::vector<int>> slabs = cut_into_slabs(mesh, cells_of, free_vertices);
  // Unless told, no more threads than idle cores (idle_cores.h): a sweep waits for its slowest slab twice, and for
  // delta once.
  const int threads = options.threads > 0 ? options.threads : std::min(omp_get_max_threads(), idle_cores());

  // Corners touching each free vertex (the vertex is the corner node or one of its three neighbours), the centre of
  // every hex around it (its first interior sample), and all interior samples of the cells bad at the start (the
  // Gauss points of every cell would multiply the work for cells that are fine anyway).
  std::vector<std::vector<Corner>> corners_of(nv);
  for (int v : free_vertices)
    for (int c : cells_of[v]) {
      const int samples = is_bad(c) ? static_cast<int>(interior_sample_weights(mesh.types[c]).size())
                          : mesh.types[c] == CellType::Hex ? 1
                                                           : 0;
      for (int sample = 0; sample < samples; ++sample) corners_of[v].push_back({c, kSample + sample});
      for (int k = 0; k < node_count(mesh.types[c]); ++k) {
        const auto& n = corner_nodes(mesh.types[c], k);
        if (std::any_of(n.begin(), n.end(), [&](int local) { return mesh.C(c, local) == v; }))
          corners_of[v].push_back({c, k});
      }
    }

  // W^-1 of each corner and interior sample of the cells around free vertices (cell_bounds.h).
  std::vector<char> around(nc, 0);
  for (int v : free_vertices)
    for (int c : cells_of[v]) around[c] = 1;
  const CornerTargets targets(mesh, options, around);
  // The corner (or sample) matrix A of a cell with nodes X, and its W^-1.
  auto corner_matrix = [&](const Corner& corner, const CellNodes& X, Eigen::Matrix3d& A) -> Eigen::Matrix3d {
    A = slot_matrix(mesh.types[corner.cell], X, corner.k);
    return targets.inverse(mesh, corner.cell, corner.k);
  };

  CornerEnergy energy;
  energy.power = options.corner_power;
  // The energy of the corners around v and, optionally, its gradient and Hessian by x_v (corner_energy.h).
  auto vertex_energy = [&](int v, Eigen::Vector3d* gradient, Eigen::Matrix3d* hessian) {
    double e = 0;
    if (gradient) {
      gradient->setZero();
      hessian->setZero();
    }
    int gathered = -1;  // corners_of[v] lists each cell's corners together: gather its nodes once
    CellNodes X;
    for (const Corner& corner : corners_of[v]) {
      const CellType type = mesh.types[corner.cell];
      if (corner.cell != gathered) {
        X = cell_nodes(mesh, corner.cell);
        gathered = corner.cell;
      }
      Eigen::Matrix3d A;
      const Eigen::Matrix3d Winv = corner_matrix(corner, X, A);
      if (!gradient) {
        e += energy(A, Winv);
        continue;
      }
      // A = sum over the cell's nodes i of x_i c_i^T: v's coefficient c (summed over the nodes that are v).
      Eigen::Vector3d coefficient = Eigen::Vector3d::Zero();
      if (corner.k >= kSample) {
        const SampleWeights& W = interior_sample_weights(type)[corner.k - kSample];
        for (int i = 0; i < node_count(type); ++i)
          if (mesh.C(corner.cell, i) == v) coefficient += W.row(i).transpose();
      } else {  // A = [x_a - x_k, x_b - x_k, x_c - x_k]: column j is +x_(n[j+1]) and -x_(n[0])
        const auto& n = corner_nodes(type, corner.k);
        for (int j = 0; j < 3; ++j) {
          if (mesh.C(corner.cell, n[j + 1]) == v) coefficient(j) += 1;
          if (mesh.C(corner.cell, n[0]) == v) coefficient(j) -= 1;
        }
      }
      Eigen::Vector3d g;
      Eigen::Matrix3d H;
      e += energy.node(A, Winv, coefficient, g, H);
      if (!std::isfinite(e)) break;
      *gradient += g;
      *hessian += H;
    }
    return e;
  };
  // Active set: a sweep visits the vertices that moved in the previous sweep, their neighbours, and the vertices of
  // nearly inverted corners (where delta, which changes from sweep to sweep, matters); elsewhere delta is negligible
  // against the corners' own sigma, so a vertex that did not move is still at its local optimum.
  std::vector<char> active(nv, 0), next_active(nv, 0);
  for (int v : free_vertices) active[v] = 1;
  // Each corner touching a free vertex once, and each cell around one once: the per-sweep checks below run over these
  // (a corner touches up to four free vertices, a cell up to eight).
  std::vector<Corner> touched_corners;
  std::vector<int> touched_cells;
  {
    std::vector<char> corner_seen(static_cast<size_t>(nc) * kCellSlots, 0), cell_seen(nc, 0);
    for (int v : free_vertices)
      for (const Corner& corner : corners_of[v]) {
        char& seen = corner_seen[static_cast<size_t>(corner.cell) * kCellSlots + corner.k];
        if (!seen) touched_corners.push_back(corner);
        seen = 1;
        if (!cell_seen[corner.cell]) touched_cells.push_back(corner.cell);
        cell_seen[corner.cell] = 1;
      }
  }
  // The state of each cell around a free vertex, kept current by the steps (a step changes only the cells around its
  // vertex, and the vertices stepped at the same time share no cell).
  struct CellState {
    bool unusable = false;
    double scaled_jacobian = 0;
  };
  std::vector<CellState> cell_state(nc);
  for (int c : touched_cells) {
    const CellJacobians j = cell_jacobians(mesh.types[c], cell_nodes(mesh, c));
    cell_state[c] = {is_unusable(j), j.scaled_jacobian};
  }
  // delta from the worst normalized corner determinant (Escobar et al.: delta^2 = eps (eps - sigma_min)).
  std::vector<double> sigma(touched_corners.size());
  auto update_delta = [&] {
    const int n = static_cast<int>(touched_corners.size());
    double sigma_min = std::numeric_limits<double>::infinity();
#pragma omp parallel for num_threads(threads) reduction(min : sigma_min)
    for (int i = 0; i < n; ++i) {
      Eigen::Matrix3d A;
      const Eigen::Matrix3d Winv = corner_matrix(touched_corners[i], cell_nodes(mesh, touched_corners[i].cell), A);
      sigma[i] = normalized_determinant(A * Winv);
      sigma_min = std::min(sigma_min, sigma[i]);
    }
    for (int i = 0; i < n; ++i) {
      if (!(sigma[i] < kNearlyInverted)) continue;
      const Corner& corner = touched_corners[i];
      const CellType type = mesh.types[corner.cell];
      if (corner.k >= kSample) {
        for (int local = 0; local < node_count(type); ++local) active[mesh.C(corner.cell, local)] = 1;
      } else {
        for (int local : corner_nodes(type, corner.k)) active[mesh.C(corner.cell, local)] = 1;
      }
    }
    constexpr double eps = 1e-3;
    energy.delta2 = sigma_min < eps ? eps * (eps - sigma_min) : 0.0;
  };

  // One Gauss-Seidel step at vertex v: how far it moved and its typical edge length.
  struct Step {
    double moved = 0, edge = 0;
  };
  auto step_vertex = [&](int v) -> Step {
    Eigen::Vector3d gx;
    Eigen::Matrix3d Hx;
    const double e0 = vertex_energy(v, &gx, &Hx);
    const Eigen::Vector3d p0 = placement.p.row(v).transpose();
    const Eigen::RowVector3d x0 = mesh.V.row(v);
    Eigen::Vector3d x_at_p0;
    Eigen::Matrix3d J;
    if (!std::isfinite(e0) || !placement.place(v, p0, x_at_p0, J)) return Step{};
    const Eigen::Matrix3d& M = movable[v];
    const Eigen::Vector3d g = M * (J.transpose() * gx);  // gradient in the movable parameter directions
    if (!(g.norm() > 0)) return Step{};
    // Typical edge length at v (the mean: in a fold some edges have collapsed and would stall the steps).
    double edge = 0;
    int edges = 0;
    for (const Corner& corner : corners_of[v])
      if (corner.k < kSample)
        for (int local : corner_nodes(mesh.types[corner.cell], corner.k))
          if (mesh.C(corner.cell, local) != v) {
            edge += (mesh.V.row(mesh.C(corner.cell, local)) - x0).norm();
            ++edges;
          }
    edge /= std::max(1, edges);
    // Newton direction: the exact Hessian in space, pulled back to the
    // parameters (J^T H J) and restricted to the movable directions; steepest descent if not positive definite.
    const Eigen::Matrix3d Hp =
        M * J.transpose() * Hx * J * M + (Eigen::Matrix3d::Identity() - M) * (J.transpose() * Hx * J).norm();
    const Eigen::LLT<Eigen::Matrix3d> llt(Hp);
    Eigen::Vector3d step =
        (llt.info() == Eigen::Success && Hp.allFinite()) ? Eigen::Vector3d(-(M * llt.solve(g))) : Eigen::Vector3d(-g);
    const double reach = (J * step).norm();
    if (reach > 0.5 * edge) step *= 0.5 * edge / reach;  // no jumps across several cells
    // A step never makes a cell around v unusable that was not before (the count of unusable cells only falls), and
    // no cell at or above options.keep_above drops below it.
    int unusable_before = 0;
    for (int c : cells_of[v]) unusable_before += cell_state[c].unusable;
    thread_local std::vector<CellState> trial;
    trial.resize(cells_of[v].size());
    auto still_valid = [&] {
      int unusable_now = 0;
      for (size_t i = 0; i < cells_of[v].size(); ++i) {
        const int c = cells_of[v][i];
        const CellJacobians j = cell_jacobians(mesh.types[c], cell_nodes(mesh, c));
        trial[i] = {is_unusable(j), j.scaled_jacobian};
        unusable_now += trial[i].unusable;
        const bool was_good = options.keep_above > 0 && cell_state[c].scaled_jacobian >= options.keep_above;
        if (unusable_now > unusable_before || (was_good && j.scaled_jacobian < options.keep_above)) return false;
      }
      return true;
    };
    bool improved = false;
    double t = options.over_relaxation;
    for (int halving = 0; halving < 30 && !improved; ++halving, t *= 0.5) {
      Eigen::Vector3d x;
      Eigen::Matrix3d unused;
      const Eigen::Vector3d p = p0 + t * step;
      if (!placement.place(v, p, x, unused)) continue;
      mesh.V.row(v) = x.transpose();
      improved = vertex_energy(v, nullptr, nullptr) < e0 + 1e-4 * t * g.dot(step) && still_valid();
      if (!improved) continue;
      placement.p.row(v) = p.transpose();
      for (size_t i = 0; i < cells_of[v].size(); ++i) cell_state[cells_of[v][i]] = trial[i];
    }
    if (!improved) mesh.V.row(v) = x0;
    const double moved_v = (mesh.V.row(v) - x0).norm();
    return Step{moved_v, edge};
  };
  std::vector<Step> steps(nv);
  for (report.sweeps = 0; report.sweeps < options.max_sweeps; ++report.sweeps) {
    update_delta();
    int visited = 0;
    // The even slabs step in parallel, then the odd ones (cut_into_slabs), each slab in its own Gauss-Seidel order.
    const int slab_count = static_cast<int>(slabs.size());
    for (int parity = 0; parity < 2; ++parity) {
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) reduction(+ : visited)
      for (int k = parity; k < slab_count; k += 2)
        for (int v : slabs[k]) {
          steps[v] = Step{};
          if (!active[v]) continue;
          ++visited;
          steps[v] = step_vertex(v);
        }
    }
    // The next sweep visits the vertices around those that moved.
    std::fill(next_active.begin(), next_active.end(), 0);
    double moved = 0, size = 0;
    for (int v : free_vertices) {
      moved = std::max(moved, steps[v].moved);
      size = std::max(size, steps[v].edge);
      if (steps[v].moved > 1e-4 * steps[v].edge)
        for (int c : cells_of[v])
          for (int i = 0; i < node_count(mesh.types[c]); ++i) next_active[mesh.C(c, i)] = 1;
    }
    active.swap(next_active);
    int unusable_left = 0;
    for (int c : touched_cells) unusable_left += cell_state[c].unusable;
    report_progress(options.progress, "untangling", (report.sweeps + 1.0) / options.max_sweeps);
    // Done when nothing is unusable and the smoothing has settled (or had a fair number of sweeps).
    if (unusable_left == 0 && (visited == 0 || moved < 1e-3 * size || report.sweeps >= 30)) break;
  }
  tally(report.inverted_after, report.degenerate_after, report.bad_after, report.min_scaled_jacobian_after);
  return report;
}

}  // namespace facehex
