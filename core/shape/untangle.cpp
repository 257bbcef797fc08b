#include "core/shape/untangle.h"

#include <omp.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

#include "core/mesh/cell_rings.h"
#include "core/mesh/corner_jacobian.h"
#include "core/shape/cell_bounds.h"
#include "core/shape/corner_energy.h"
#include "core/shape/slab_schedule.h"
#include "core/util/idle_cores.h"

namespace facehex {
namespace {

struct Corner {
  int cell, slot;  // slot: corner index, or kSampleSlot + s for the cell's interior sample s (cell_bounds.h)
};

constexpr double kNearlyInverted = 0.1;  // normalized corner determinant below which a vertex is always revisited
constexpr double kDeltaEpsilon = 1e-3;   // delta^2 = eps (eps - sigma_min) while sigma_min < eps (Escobar et al.)
constexpr double kArmijo = 1e-4;         // sufficient decrease of a step, relative to its slope
constexpr int kHalvings = 15;            // line search trials (the last is 2^-14 of the first step)
constexpr double kLongestStep = 0.5;     // a step moves its vertex at most this share of its mean edge
constexpr double kMovedBy = 1e-4;        // a vertex that moved more than this share of its edge wakes its neighbours
constexpr double kSettledBy = 1e-3;      // a sweep whose largest move is below this share of the edges has settled
constexpr int kFairSweeps = 30;          // a smoothing with nothing unusable left stops after this many sweeps
// A repair (not a whole-mesh relaxation, whose sweeps improve every cell's shape whatever the folds do) stops when
// its unusable cells have not become fewer for kStalledWork vertex steps, but at least kLeastStalledSweeps and at most
// kStalledSweeps sweeps: what it could untangle from there, it has. Patience measured in work: a pass over thousands
// of vertices that has stalled costs seconds a sweep and the later passes, over the few vertices around what is left,
// finish the untangling for a fraction of that; a pass over a few hundred vertices is cheap to keep going.
constexpr int kStalledSweeps = 20;
constexpr int kLeastStalledSweeps = 5;
constexpr int kStalledWork = 10000;

struct CellState {
  bool unusable = false;
  double scaled_jacobian = 0;
};

// One Gauss-Seidel step at a vertex: how far it moved, its typical edge length and how much it lowered the energy.
struct Step {
  double moved = 0, edge = 0, lowered = 0;
};

// One call of untangle(): the free vertices, the corners around them with their target shapes, the state of the cells
// around them, and the sweeps over them.
class LocalShapeSolver {
 public:
  LocalShapeSolver(VolumeMesh& mesh, VertexPlacement& placement, const UntangleOptions& options,
                   const CellBounds& bounds)
      : mesh_(mesh), placement_(placement), options_(options), bounds_(bounds) {
    energy_.power = options.corner_power;
    // Unless told, no more threads than idle cores (idle_cores.h): a sweep waits for its slowest slab twice, and for
    // delta once.
    threads_ = options.threads > 0 ? options.threads : std::min(omp_get_max_threads(), idle_cores());
    select_free_vertices();
    gather_corners();
    stalled_after_ = std::clamp(kStalledWork / std::max(1, free_vertex_count()), kLeastStalledSweeps, kStalledSweeps);
    if (options_.tether_weight > 0 && options_.tether.rows() == mesh_.num_vertices()) {
      tether_scale_.assign(mesh_.num_vertices(), 0);
      for (int v : free_vertices_) {
        const double h = mean_edge(v);
        tether_scale_[v] = h > 0 ? options_.tether_weight / (h * h) : 0;
      }
    }
  }

  int free_vertex_count() const { return static_cast<int>(free_vertices_.size()); }
  // The last run() stopped because its unusable cells stopped becoming fewer.
  bool stalled() const { return stalled_; }
  // The last run() stopped because a sweep lowered the energy by little (UntangleOptions::settled_energy_share).
  bool settled() const { return settled_; }
  long vertex_steps() const { return vertex_steps_; }

  // Sweeps until nothing is unusable and the smoothing has settled, the repair has stalled (stalled()), or max_sweeps;
  // returns the sweeps made.
  int run() {
    const int nv = mesh_.num_vertices();
    active_.assign(nv, 0);
    for (int v : free_vertices_) active_[v] = 1;
    std::vector<char> next_active(nv, 0);
    std::vector<Step> steps(nv);
    int sweeps = 0, fewest_unusable = std::numeric_limits<int>::max(), since_fewer = 0;
    double lowered_by_all = 0;  // the energy the sweeps so far took off
    while (sweeps < options_.max_sweeps) {
      update_delta();
      int visited = 0;
      // The even slabs step in parallel, then the odd ones (slab_schedule.h), each slab in its own Gauss-Seidel order.
      const int slab_count = static_cast<int>(slabs_.size());
      for (int parity = 0; parity < 2; ++parity) {
#pragma omp parallel for num_threads(threads_) schedule(dynamic, 1) reduction(+ : visited)
        for (int k = parity; k < slab_count; k += 2)
          for (int v : slabs_[k]) {
            steps[v] = Step{};
            if (!active_[v]) continue;
            ++visited;
            steps[v] = step_vertex(v);
          }
      }
      // The next sweep visits the vertices around those that moved and lowered the energy by at least their share
      // of a settled sweep's decrease (settled_energy_share): a step that took off less has hardly moved its
      // neighbours' optimum.
      std::fill(next_active.begin(), next_active.end(), 0);
      double moved = 0, size = 0, lowered = 0;  // summed in vertex order: the same for every thread count
      for (int v : free_vertices_) lowered += steps[v].lowered;
      lowered_by_all += lowered;
      const double settled_step = options_.settled_energy_share * lowered_by_all / free_vertex_count();
      for (int v : free_vertices_) {
        moved = std::max(moved, steps[v].moved);
        size = std::max(size, steps[v].edge);
        if (steps[v].moved > kMovedBy * steps[v].edge && steps[v].lowered >= settled_step)
          for (int c : cells_of_[v])
            for (int i = 0; i < node_count(mesh_.types[c]); ++i) next_active[mesh_.C(c, i)] = 1;
      }
      active_.swap(next_active);
      int unusable_left = 0;
      for (int c : touched_cells_) unusable_left += cell_state_[c].unusable;
      ++sweeps;
      vertex_steps_ += visited;
      report_progress(options_.progress, "untangling", static_cast<double>(sweeps) / options_.max_sweeps);
      if (unusable_left == 0 && (visited == 0 || moved < kSettledBy * size || sweeps > kFairSweeps)) break;
      settled_ = lowered < options_.settled_energy_share * lowered_by_all;
      if (settled_) break;
      since_fewer = unusable_left < fewest_unusable ? 0 : since_fewer + 1;
      fewest_unusable = std::min(fewest_unusable, unusable_left);
      stalled_ = unusable_left > 0 && !options_.whole_mesh && since_fewer >= stalled_after_;
      if (stalled_) break;
    }
    return sweeps;
  }

 private:
  // The movable vertices within `rings` cell rings of a bad cell (of an unusable one with seed_unusable_only), or all
  // of them with whole_mesh; the cells around each vertex.
  void select_free_vertices() {
    const int nc = mesh_.num_cells(), nv = mesh_.num_vertices();
    cells_of_.assign(nv, {});
    for (int c = 0; c < nc; ++c)
      for (int i = 0; i < node_count(mesh_.types[c]); ++i) cells_of_[mesh_.C(c, i)].push_back(c);
    std::vector<char> region(nv, 1);
    if (!options_.whole_mesh) {
      std::vector<char> in_bad_cell(nv, 0);
      for (int c = 0; c < nc; ++c)
        if (options_.seed_unusable_only ? is_unusable(mesh_.types[c], cell_nodes(mesh_, c)) : bounds_.is_bad(mesh_, c))
          for (int i = 0; i < node_count(mesh_.types[c]); ++i) in_bad_cell[mesh_.C(c, i)] = 1;
      region = within_cell_rings(mesh_, std::move(in_bad_cell), options_.rings);
    }
    for (int v = 0; v < nv; ++v)
      if (region[v] && !placement_.movable[v].isZero()) free_vertices_.push_back(v);
    slabs_ = slab_schedule(mesh_, cells_of_, free_vertices_);
  }

  // Corners touching each free vertex (the vertex is the corner node or one of its three neighbours), the centre of
  // every hex around it (its first interior sample), and all interior samples of the cells bad at the start (the
  // Gauss points of every cell would multiply the work for cells that are fine anyway); their targets; each corner and
  // each cell around a free vertex once, for the per-sweep checks (a corner touches up to four free vertices, a cell
  // up to eight), and the cells' states.
  void gather_corners() {
    const int nc = mesh_.num_cells();
    corners_of_.assign(mesh_.num_vertices(), {});
    for (int v : free_vertices_)
      for (int c : cells_of_[v]) {
        const CellType type = mesh_.types[c];
        const int samples = bounds_.is_bad(mesh_, c) ? static_cast<int>(interior_sample_weights(type).size())
                            : type == CellType::Hex  ? 1
                                                     : 0;
        for (int sample = 0; sample < samples; ++sample) corners_of_[v].push_back({c, kSampleSlot + sample});
        for (int k = 0; k < node_count(type); ++k) {
          const auto& n = corner_nodes(type, k);
          if (std::any_of(n.begin(), n.end(), [&](int local) { return mesh_.C(c, local) == v; }))
            corners_of_[v].push_back({c, k});
        }
      }
    std::vector<char> corner_seen(static_cast<size_t>(nc) * kCellSlots, 0), cell_seen(nc, 0);
    for (int v : free_vertices_)
      for (const Corner& corner : corners_of_[v]) {
        char& seen = corner_seen[static_cast<size_t>(corner.cell) * kCellSlots + corner.slot];
        if (!seen) touched_corners_.push_back(corner);
        seen = 1;
        if (!cell_seen[corner.cell]) touched_cells_.push_back(corner.cell);
        cell_seen[corner.cell] = 1;
      }
    std::sort(touched_corners_.begin(), touched_corners_.end(), [](const Corner& a, const Corner& b) {
      return a.cell < b.cell || (a.cell == b.cell && a.slot < b.slot);
    });
    targets_ = std::make_unique<CornerTargets>(mesh_, options_, cell_seen, threads_);
    // Each corner's target and how it moves with the vertex: A = sum over the cell's nodes i of x_i c_i^T, so S = A
    // W^-1 moves by x w^T with w = W^-T c, c the vertex's coefficient (summed over the nodes that are the vertex).
    corner_targets_.assign(mesh_.num_vertices(), {});
    corner_weights_.assign(mesh_.num_vertices(), {});
    for (int v : free_vertices_)
      for (const Corner& corner : corners_of_[v]) {
        const CellType type = mesh_.types[corner.cell];
        Eigen::Vector3d coefficient = Eigen::Vector3d::Zero();
        if (corner.slot >= kSampleSlot) {
          const SampleWeights& W = interior_sample_weights(type)[corner.slot - kSampleSlot];
          for (int i = 0; i < node_count(type); ++i)
            if (mesh_.C(corner.cell, i) == v) coefficient += W.row(i).transpose();
        } else {  // A = [x_a - x_k, x_b - x_k, x_c - x_k]: column j is +x_(n[j+1]) and -x_(n[0])
          const auto& n = corner_nodes(type, corner.slot);
          for (int j = 0; j < 3; ++j) {
            if (mesh_.C(corner.cell, n[j + 1]) == v) coefficient(j) += 1;
            if (mesh_.C(corner.cell, n[0]) == v) coefficient(j) -= 1;
          }
        }
        const Eigen::Matrix3d& Winv = targets_->inverse(mesh_, corner.cell, corner.slot);
        corner_targets_[v].push_back(&Winv);
        corner_weights_[v].push_back(Winv.transpose() * coefficient);
      }
    sigma_.resize(touched_corners_.size());
    // Each cell's state is kept current by the steps: a step changes only the cells around its vertex, and the
    // vertices stepped at the same time share no cell.
    cell_state_.assign(nc, {});
    for (int c : touched_cells_) {
      const CellJacobians j = cell_jacobians(mesh_.types[c], cell_nodes(mesh_, c));
      cell_state_[c] = {is_unusable(j), j.scaled_jacobian};
    }
  }

  // The corner (or sample) matrix A of a cell with nodes X, and its target W^-1.
  const Eigen::Matrix3d& corner_matrix(const Corner& corner, const CellNodes& X, Eigen::Matrix3d& A) const {
    A = slot_matrix(mesh_.types[corner.cell], X, corner.slot);
    return targets_->inverse(mesh_, corner.cell, corner.slot);
  }

  // The energy of the corners around v and, optionally, its gradient and Hessian by x_v (corner_energy.h; both or
  // neither).
  double vertex_energy(int v, Eigen::Vector3d* gradient, Eigen::Matrix3d* hessian) const {
    const std::vector<Corner>& corners = corners_of_[v];
    const int n = static_cast<int>(corners.size());
    thread_local std::vector<Eigen::Matrix3d> S;
    S.resize(n);
    int gathered = -1;  // corners_of_[v] lists each cell's corners together: gather its nodes once
    CellNodes X;
    for (int i = 0; i < n; ++i) {
      if (corners[i].cell != gathered) {
        X = cell_nodes(mesh_, corners[i].cell);
        gathered = corners[i].cell;
      }
      S[i].noalias() = slot_matrix(mesh_.types[corners[i].cell], X, corners[i].slot) * *corner_targets_[v][i];
    }
    double e =
        gradient ? energy_.sum(S.data(), corner_weights_[v].data(), n, *gradient, *hessian) : energy_.sum(S.data(), n);
    if (!tether_scale_.empty() && tether_scale_[v] > 0) {
      const Eigen::Vector3d d = (mesh_.V.row(v) - options_.tether.row(v)).transpose();
      e += tether_scale_[v] * d.squaredNorm();
      if (gradient) {
        *gradient += 2 * tether_scale_[v] * d;
        hessian->diagonal().array() += 2 * tether_scale_[v];
      }
    }
    return e;
  }

  // delta from the worst normalized corner determinant; the vertices of nearly inverted corners are activated (where
  // delta, which changes from sweep to sweep, matters; elsewhere it is negligible against the corners' own sigma, so a
  // vertex that did not move is still at its local optimum).
  void update_delta() {
    const int n = static_cast<int>(touched_corners_.size());
    double sigma_min = std::numeric_limits<double>::infinity();
#pragma omp parallel num_threads(threads_) reduction(min : sigma_min)
    {
      int gathered = -1;  // touched_corners_ lists each cell's corners together: gather its nodes once
      CellNodes X;
#pragma omp for schedule(static)
      for (int i = 0; i < n; ++i) {
        const Corner& corner = touched_corners_[i];
        if (corner.cell != gathered) {
          X = cell_nodes(mesh_, corner.cell);
          gathered = corner.cell;
        }
        Eigen::Matrix3d A;
        const Eigen::Matrix3d& Winv = corner_matrix(corner, X, A);
        sigma_[i] = normalized_determinant(A * Winv);
        sigma_min = std::min(sigma_min, sigma_[i]);
      }
    }
    for (int i = 0; i < n; ++i) {
      if (!(sigma_[i] < kNearlyInverted)) continue;
      const Corner& corner = touched_corners_[i];
      const CellType type = mesh_.types[corner.cell];
      if (corner.slot >= kSampleSlot) {
        for (int local = 0; local < node_count(type); ++local) active_[mesh_.C(corner.cell, local)] = 1;
      } else {
        for (int local : corner_nodes(type, corner.slot)) active_[mesh_.C(corner.cell, local)] = 1;
      }
    }
    energy_.delta2 = sigma_min < kDeltaEpsilon ? kDeltaEpsilon * (kDeltaEpsilon - sigma_min) : 0.0;
  }

  // The mean length of the edges at v (the mean: in a fold some edges have collapsed and would stall the steps).
  double mean_edge(int v) const {
    const Eigen::RowVector3d x = mesh_.V.row(v);
    double edge = 0;
    int edges = 0;
    for (const Corner& corner : corners_of_[v])
      if (corner.slot < kSampleSlot)
        for (int local : corner_nodes(mesh_.types[corner.cell], corner.slot))
          if (mesh_.C(corner.cell, local) != v) {
            edge += (mesh_.V.row(mesh_.C(corner.cell, local)) - x).norm();
            ++edges;
          }
    return edge / std::max(1, edges);
  }

  // True if no cell around v is unusable that was not (their count only falls: unusable_before) and no cell at or
  // above keep_above dropped below it; the cells' new states in `trial`.
  bool still_valid(int v, int unusable_before, std::vector<CellState>& trial) const {
    int unusable_now = 0;
    for (size_t i = 0; i < cells_of_[v].size(); ++i) {
      const int c = cells_of_[v][i];
      const CellJacobians j = cell_jacobians(mesh_.types[c], cell_nodes(mesh_, c));
      trial[i] = {is_unusable(j), j.scaled_jacobian};
      unusable_now += trial[i].unusable;
      const bool was_good = options_.keep_above > 0 && cell_state_[c].scaled_jacobian >= options_.keep_above;
      if (unusable_now > unusable_before || (was_good && j.scaled_jacobian < options_.keep_above)) return false;
    }
    return true;
  }

  // A Newton step at v in its movable parameter directions: the exact Hessian in space pulled back to the parameters
  // (J^T H J), steepest descent where that is not positive definite; then a backtracking line search from
  // over_relaxation times the step that keeps every cell around v valid (still_valid).
  Step step_vertex(int v) {
    Eigen::Vector3d gx;
    Eigen::Matrix3d Hx;
    const double e0 = vertex_energy(v, &gx, &Hx);
    const Eigen::Vector3d p0 = placement_.p.row(v).transpose();
    const Eigen::RowVector3d x0 = mesh_.V.row(v);
    Eigen::Vector3d x_at_p0;
    Eigen::Matrix3d J;
    if (!std::isfinite(e0) || !placement_.place(v, p0, x_at_p0, J)) return Step{};
    const Eigen::Matrix3d& M = placement_.movable[v];
    const Eigen::Vector3d g = M * (J.transpose() * gx);  // gradient in the movable parameter directions
    if (!(g.norm() > 0)) return Step{};
    const double edge = mean_edge(v);
    const Eigen::Matrix3d Hp =
        M * J.transpose() * Hx * J * M + (Eigen::Matrix3d::Identity() - M) * (J.transpose() * Hx * J).norm();
    const Eigen::LLT<Eigen::Matrix3d> llt(Hp);
    Eigen::Vector3d step =
        (llt.info() == Eigen::Success && Hp.allFinite()) ? Eigen::Vector3d(-(M * llt.solve(g))) : Eigen::Vector3d(-g);
    const double reach = (J * step).norm();
    if (reach > kLongestStep * edge) step *= kLongestStep * edge / reach;  // no jumps across several cells
    int unusable_before = 0;
    for (int c : cells_of_[v]) unusable_before += cell_state_[c].unusable;
    thread_local std::vector<CellState> trial;
    trial.resize(cells_of_[v].size());
    bool improved = false;
    double lowered = 0;
    double t = options_.over_relaxation;
    for (int halving = 0; halving < kHalvings && !improved; ++halving, t *= 0.5) {
      Eigen::Vector3d x;
      Eigen::Matrix3d unused;
      const Eigen::Vector3d p = p0 + t * step;
      if (!placement_.place(v, p, x, unused)) continue;
      mesh_.V.row(v) = x.transpose();
      const double e = vertex_energy(v, nullptr, nullptr);
      improved = e < e0 + kArmijo * t * g.dot(step) && still_valid(v, unusable_before, trial);
      if (!improved) continue;
      placement_.p.row(v) = p.transpose();
      for (size_t i = 0; i < cells_of_[v].size(); ++i) cell_state_[cells_of_[v][i]] = trial[i];
      lowered = e0 - e;
    }
    if (!improved) mesh_.V.row(v) = x0;
    return Step{(mesh_.V.row(v) - x0).norm(), edge, lowered};
  }

  VolumeMesh& mesh_;
  VertexPlacement& placement_;
  const UntangleOptions& options_;
  const CellBounds& bounds_;
  int threads_ = 1;
  bool stalled_ = false;
  bool settled_ = false;
  long vertex_steps_ = 0;
  int stalled_after_ = kStalledSweeps;  // sweeps without fewer unusable cells after which a repair stops
  CornerEnergy energy_;                 // delta2 follows the worst corner (update_delta)
  std::vector<int> free_vertices_;
  std::vector<std::vector<int>> cells_of_, slabs_;
  std::vector<std::vector<Corner>> corners_of_;
  std::vector<std::vector<const Eigen::Matrix3d*>> corner_targets_;  // #V, per corner of corners_of_: its W^-1
  std::vector<std::vector<Eigen::Vector3d>> corner_weights_;         // #V, per corner of corners_of_: its w
  std::vector<Corner> touched_corners_;
  std::vector<int> touched_cells_;
  std::unique_ptr<CornerTargets> targets_;
  std::vector<CellState> cell_state_;  // #C, current for the touched cells
  std::vector<double> sigma_;          // per touched corner, its last normalized determinant
  std::vector<char> active_;           // #V: vertices the next sweep visits
  std::vector<double> tether_scale_;   // #V: tether_weight / h^2 of each free vertex, or empty without a tether
};

}  // namespace

UntangleOptions relaxation_options(UntangleOptions repair) {
  UntangleOptions relax = std::move(repair);
  relax.whole_mesh = true;
  relax.over_relaxation = 1.8;
  relax.keep_above = 0.05;
  relax.corner_power = 1;
  relax.max_sweeps = 40;
  relax.settled_energy_share = 1e-3;
  return relax;
}

UntangleReport untangle(VolumeMesh& mesh, VertexPlacement& placement, const UntangleOptions& options) {
  UntangleReport report;
  const CellBounds bounds(mesh, options);
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
  LocalShapeSolver solver(mesh, placement, options, bounds);
  report.free_vertices = solver.free_vertex_count();
  report.sweeps = solver.run();
  report.stalled_passes = solver.stalled();
  report.settled = solver.settled();
  report.vertex_steps = solver.vertex_steps();
  tally(report.inverted_after, report.degenerate_after, report.bad_after, report.min_scaled_jacobian_after);
  return report;
}

}  // namespace facehex
