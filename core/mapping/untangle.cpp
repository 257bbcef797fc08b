#include "core/mapping/untangle.h"

#include <omp.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "core/mesh/corner_jacobian.h"
#include "core/util/error.h"
#include "core/util/idle_cores.h"

namespace facehex {
namespace {

struct Corner {
  int cell, k;  // k: corner index, or kSample + s for the cell's interior sample s (corner_jacobian.h)
};
constexpr int kSample = 8;
constexpr double kReferenceShare = 0.5;  // see UntangleOptions::reference_scaled_jacobian
constexpr double kNearlyInverted = 0.1;  // normalized corner determinant below which a vertex is always revisited

// Inverse ideal corner matrices W_k^-1 per cell type and corner.
const Eigen::Matrix3d& ideal_inverse(CellType type, int k) {
  static const auto table = [] {
    std::array<std::array<Eigen::Matrix3d, 8>, 3> t;
    const CellType types[3] = {CellType::Tet, CellType::Wedge, CellType::Hex};
    for (int i = 0; i < 3; ++i) {
      const CellNodes X = ideal_cell(types[i]);
      for (int c = 0; c < node_count(types[i]); ++c) t[i][c] = corner_jacobian(types[i], X, c).inverse();
    }
    return t;
  }();
  return table[type == CellType::Tet ? 0 : type == CellType::Wedge ? 1 : 2][k];
}

// The corner's normalized determinant: sigma / s^3 with s^2 = |S|_F^2 / 3, in [-1, 1], 1 only for the ideal corner.
// Regularizing it (rather than det S, which scales with the cell's volume) treats small and large cells alike.
double normalized_determinant(const Eigen::Matrix3d& S) {
  const double s2 = S.squaredNorm() / 3;
  return S.determinant() / (s2 * std::sqrt(s2));
}

// W^-1 for a target corner W whose ideal counterpart has inverse ideal_inv. With M = W ideal_inv (the target relative
// to the ideal corner) and its polar decomposition M = R U, the stretch U is scaled to unit determinant and moved
// `towards_ideal` of the way to the identity; R is dropped, since the energy does not change when S is rotated from
// the right. A nearly flat or inverted target corner gives the ideal one.
Eigen::Matrix3d target_corner_inverse(const Eigen::Matrix3d& W, const Eigen::Matrix3d& ideal_inv,
                                      double towards_ideal) {
  const Eigen::Matrix3d M = W * ideal_inv;
  if (!(normalized_determinant(M) > kNearlyInverted)) return ideal_inv;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(M.transpose() * M);
  Eigen::Vector3d stretch = eigen.eigenvalues().cwiseMax(0).cwiseSqrt();
  stretch /= std::cbrt(stretch.prod());
  const Eigen::Vector3d blended = (1 - towards_ideal) * stretch.array() + towards_ideal;
  return ideal_inv * eigen.eigenvectors() * blended.cwiseInverse().asDiagonal() * eigen.eigenvectors().transpose();
}

struct Energy {
  double delta2 = 0;  // delta^2, dimensionless
  double power = 1;   // UntangleOptions::corner_power

  // eta = h(sigma^)^(-2/3) of one corner (the inverse mean ratio |S|^2 / (3 det(S)^(2/3)) when delta = 0) and,
  // optionally, its gradient with respect to the corner matrix A.
  double corner(const Eigen::Matrix3d& A, const Eigen::Matrix3d& Winv, Eigen::Matrix3d* dA) const {
    const Eigen::Matrix3d S = A * Winv;
    const double s2 = S.squaredNorm() / 3;
    if (!(s2 > 0)) return std::numeric_limits<double>::infinity();
    const double s3 = s2 * std::sqrt(s2);
    const double sigma = S.determinant() / s3;
    const double root = std::sqrt(sigma * sigma + 4 * delta2);
    const double h = 0.5 * (sigma + root);
    if (!(h > 0)) return std::numeric_limits<double>::infinity();
    const double eta = 1.0 / std::cbrt(h * h);
    if (dA) {
      const double dh = 0.5 * (1 + sigma / root);
      Eigen::Matrix3d cof;  // d det(S) / d S
      cof.col(0) = S.col(1).cross(S.col(2));
      cof.col(1) = S.col(2).cross(S.col(0));
      cof.col(2) = S.col(0).cross(S.col(1));
      const Eigen::Matrix3d dsigma = cof / s3 - sigma * S / s2;
      const Eigen::Matrix3d dS = -(2.0 / 3.0) * eta / h * dh * dsigma;
      *dA = dS * Winv.transpose();
      if (power != 1) *dA *= power * std::pow(eta, power - 1);
    }
    return power == 1 ? eta : std::pow(eta, power);
  }
};

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

std::vector<char> within_cell_rings(const VolumeMesh& mesh, std::vector<char> marked, int rings) {
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<char> grown = marked;
    for (int c = 0; c < mesh.num_cells(); ++c) {
      bool touches = false;
      for (int i = 0; i < node_count(mesh.types[c]); ++i) touches |= marked[mesh.C(c, i)] != 0;
      if (touches)
        for (int i = 0; i < node_count(mesh.types[c]); ++i) grown[mesh.C(c, i)] = 1;
    }
    marked.swap(grown);
  }
  return marked;
}

VertexPlacement spatial_placement(const Eigen::MatrixXd& V, const std::vector<char>& fixed) {
  VertexPlacement placement;
  placement.p = V;
  placement.movable.resize(fixed.size());
  for (size_t v = 0; v < fixed.size(); ++v)
    placement.movable[v] = fixed[v] ? Eigen::Matrix3d::Zero().eval() : Eigen::Matrix3d::Identity().eval();
  placement.place = [](int, const Eigen::Vector3d& q, Eigen::Vector3d& x, Eigen::Matrix3d& dxdq) {
    x = q;
    dxdq.setIdentity();
    return true;
  };
  return placement;
}

UntangleReport untangle(VolumeMesh& mesh, VertexPlacement& placement, const UntangleOptions& options) {
  const std::vector<Eigen::Matrix3d>& movable = placement.movable;
  UntangleReport report;
  const int nc = mesh.num_cells(), nv = mesh.num_vertices();
  auto scaled = [&](int c) { return scaled_jacobian(mesh.types[c], cell_nodes(mesh, c)); };
  if (options.reference_scaled_jacobian.size() != 0 && options.reference_scaled_jacobian.size() != nc)
    throw Error("untangle", "the reference scaled Jacobians do not match the mesh's cells");
  if (options.target && (options.target->num_cells() != nc || options.target->types != mesh.types ||
                         options.target->C.cols() != mesh.C.cols() || options.target->C != mesh.C))
    throw Error("untangle", "the target mesh does not have the mesh's cells");
  auto bound = [&](int c) {
    return options.reference_scaled_jacobian.size() == 0
               ? options.min_scaled_jacobian
               : std::min(options.min_scaled_jacobian, kReferenceShare * options.reference_scaled_jacobian(c));
  };
  auto is_bad = [&](int c) {
    return min_corner_determinant(mesh.types[c], cell_nodes(mesh, c)) <= 0 || scaled(c) < bound(c);
  };
  auto unusable = [&](int c) { return is_unusable(mesh.types[c], cell_nodes(mesh, c)); };
  auto tally = [&](int& inverted, int& degenerate, int& bad, double& min_sj) {
    inverted = degenerate = bad = 0;
    min_sj = 1;
    for (int c = 0; c < nc; ++c) {
      const bool is_inverted = min_corner_determinant(mesh.types[c], cell_nodes(mesh, c)) <= 0;
      inverted += is_inverted;
      degenerate += !is_inverted && unusable(c);
      bad += is_bad(c);
      min_sj = std::min(min_sj, scaled(c));
    }
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

  // W^-1 of each corner and interior sample of the cells around free vertices: the ideal cell's, or the target's
  // moved towards the ideal by target_towards_ideal times the corner's distortion in the mesh as given.
  const int slots = kSample + 9;
  std::vector<Eigen::Matrix3d> target_inverse;
  if (options.target) {
    target_inverse.resize(static_cast<size_t>(nc) * slots);
    std::vector<char> needed(nc, 0);
    for (int v : free_vertices)
      for (int c : cells_of[v]) needed[c] = 1;
    auto target = [&](const Eigen::Matrix3d& W, const Eigen::Matrix3d& A, const Eigen::Matrix3d& ideal_inv) {
      const double eta = Energy{}.corner(A, W.inverse(), nullptr);  // 1 where A has W's shape
      const double distortion = std::isfinite(eta) && eta > 0 ? std::clamp(1 - 1 / eta, 0.0, 1.0) : 1.0;
      return target_corner_inverse(W, ideal_inv, options.target_towards_ideal * distortion);
    };
    for (int c = 0; c < nc; ++c) {
      if (!needed[c]) continue;
      const CellType type = mesh.types[c];
      const CellNodes Xt = cell_nodes(*options.target, c), X = cell_nodes(mesh, c);
      for (int k = 0; k < node_count(type); ++k)
        target_inverse[c * slots + k] =
            target(corner_jacobian(type, Xt, k), corner_jacobian(type, X, k), ideal_inverse(type, k));
      const auto& samples = interior_sample_weights(type);
      for (size_t s = 0; s < samples.size(); ++s)
        target_inverse[c * slots + kSample + s] =
            target(Xt.transpose() * samples[s], X.transpose() * samples[s], Eigen::Matrix3d::Identity());
    }
  }
  // The corner (or sample) matrix A of a cell with nodes X, and its W^-1.
  auto corner_matrix = [&](const Corner& corner, const CellNodes& X, Eigen::Matrix3d& A) -> Eigen::Matrix3d {
    const CellType type = mesh.types[corner.cell];
    A = corner.k >= kSample ? (X.transpose() * interior_sample_weights(type)[corner.k - kSample]).eval()
                            : corner_jacobian(type, X, corner.k);
    if (options.target) return target_inverse[corner.cell * slots + corner.k];
    return corner.k >= kSample ? Eigen::Matrix3d::Identity() : ideal_inverse(type, corner.k);
  };

  Energy energy;
  energy.power = options.corner_power;
  auto vertex_energy = [&](int v, Eigen::Vector3d* gradient) {
    double e = 0;
    if (gradient) gradient->setZero();
    int gathered = -1;  // corners_of[v] lists each cell's corners together: gather its nodes once
    CellNodes X;
    for (const Corner& corner : corners_of[v]) {
      const CellType type = mesh.types[corner.cell];
      if (corner.cell != gathered) {
        X = cell_nodes(mesh, corner.cell);
        gathered = corner.cell;
      }
      Eigen::Matrix3d A, dA;
      const Eigen::Matrix3d Winv = corner_matrix(corner, X, A);
      e += energy.corner(A, Winv, gradient ? &dA : nullptr);
      if (!gradient) continue;
      if (corner.k >= kSample) {  // A = X^T W: node i contributes dA * W.row(i)^T
        const SampleWeights& W = interior_sample_weights(type)[corner.k - kSample];
        for (int i = 0; i < node_count(type); ++i)
          if (mesh.C(corner.cell, i) == v) *gradient += dA * W.row(i).transpose();
        continue;
      }
      const auto& n = corner_nodes(type, corner.k);
      // A = [x_a - x_k, x_b - x_k, x_c - x_k]: column j is +x_(n[j+1]) and -x_(n[0]).
      for (int j = 0; j < 3; ++j) {
        if (mesh.C(corner.cell, n[j + 1]) == v) *gradient += dA.col(j);
        if (mesh.C(corner.cell, n[0]) == v) *gradient -= dA.col(j);
      }
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
    std::vector<char> corner_seen(static_cast<size_t>(nc) * slots, 0), cell_seen(nc, 0);
    for (int v : free_vertices)
      for (const Corner& corner : corners_of[v]) {
        char& seen = corner_seen[static_cast<size_t>(corner.cell) * slots + corner.k];
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
  std::vector<Eigen::Matrix3d> hessian(nv);  // each vertex's last finite-difference Hessian in space
  std::vector<char> has_hessian(nv, 0);
  auto step_vertex = [&](int v) -> Step {
    Eigen::Vector3d gx;
    const double e0 = vertex_energy(v, &gx);
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
    // Newton direction: Hessian in space by finite differences of the analytic gradient, pulled back to the
    // parameters (J^T H J) and restricted to the movable directions; steepest descent if not positive definite.
    // The finite differences are refreshed every options.hessian_every_sweeps sweeps and reused in between.
    Eigen::Matrix3d& Hx = hessian[v];
    if (!has_hessian[v] || report.sweeps % std::max(1, options.hessian_every_sweeps) == 0) {
      const double h = 1e-5 * edge;
      for (int d = 0; d < 3; ++d) {
        Eigen::Vector3d gd;
        mesh.V(v, d) += h;
        vertex_energy(v, &gd);
        mesh.V(v, d) = x0(d);
        Hx.col(d) = (gd - gx) / h;
      }
      Hx = 0.5 * (Hx + Hx.transpose()).eval();
      has_hessian[v] = 1;
    }
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
      improved = vertex_energy(v, nullptr) < e0 + 1e-4 * t * g.dot(step) && still_valid();
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
