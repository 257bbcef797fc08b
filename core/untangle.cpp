#include "core/untangle.h"

#include "core/corner_jacobian.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <set>

namespace facehex {
namespace {

struct Corner {
  int cell, k;
};

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

struct Energy {
  double delta2 = 0;  // delta^2

  // eta of one corner and, optionally, its gradient with respect to the corner matrix A.
  double corner(const Eigen::Matrix3d& A, const Eigen::Matrix3d& Winv, Eigen::Matrix3d* dA) const {
    const Eigen::Matrix3d S = A * Winv;
    const double sigma = S.determinant();
    const double root = std::sqrt(sigma * sigma + 4 * delta2);
    const double h = 0.5 * (sigma + root);
    if (!(h > 0)) return std::numeric_limits<double>::infinity();
    const double f = S.squaredNorm();
    const double h23 = std::cbrt(h * h);
    const double eta = f / (3 * h23);
    if (dA) {
      const double dh = 0.5 * (1 + sigma / root);
      Eigen::Matrix3d cof;  // d sigma / d S
      cof.col(0) = S.col(1).cross(S.col(2));
      cof.col(1) = S.col(2).cross(S.col(0));
      cof.col(2) = S.col(0).cross(S.col(1));
      const Eigen::Matrix3d dS = 2 * S / (3 * h23) - (2.0 / 3.0) * eta / h * dh * cof;
      *dA = dS * Winv.transpose();
    }
    return eta;
  }
};

}  // namespace

MotionConstraints fixed_or_free(const std::vector<char>& fixed) {
  MotionConstraints motion(fixed.size());
  for (size_t v = 0; v < fixed.size(); ++v)
    motion[v] = fixed[v] ? Eigen::Matrix3d::Zero().eval() : Eigen::Matrix3d::Identity().eval();
  return motion;
}

UntangleReport untangle(VolumeMesh& mesh, const MotionConstraints& motion, const UntangleOptions& options) {
  UntangleReport report;
  const int nc = mesh.num_cells(), nv = mesh.num_vertices();
  auto scaled = [&](int c) { return scaled_jacobian(mesh.types[c], cell_nodes(mesh, c)); };
  auto is_bad = [&](int c) {
    return min_corner_determinant(mesh.types[c], cell_nodes(mesh, c)) <= 0 || scaled(c) < options.min_scaled_jacobian;
  };
  auto tally = [&](int& inverted, int& bad, double& min_sj) {
    inverted = bad = 0;
    min_sj = 1;
    for (int c = 0; c < nc; ++c) {
      inverted += min_corner_determinant(mesh.types[c], cell_nodes(mesh, c)) <= 0;
      bad += is_bad(c);
      min_sj = std::min(min_sj, scaled(c));
    }
  };
  tally(report.inverted_before, report.bad_before, report.min_scaled_jacobian_before);
  if (report.bad_before == 0) {
    report.inverted_after = report.inverted_before;
    report.min_scaled_jacobian_after = report.min_scaled_jacobian_before;
    return report;
  }

  // Vertex -> cells, and the free vertices within `rings` rings of a bad cell.
  std::vector<std::vector<int>> cells_of(nv);
  for (int c = 0; c < nc; ++c)
    for (int i = 0; i < node_count(mesh.types[c]); ++i) cells_of[mesh.C(c, i)].push_back(c);
  std::set<int> region;
  for (int c = 0; c < nc; ++c)
    if (is_bad(c))
      for (int i = 0; i < node_count(mesh.types[c]); ++i) region.insert(mesh.C(c, i));
  for (int r = 0; r < options.rings; ++r) {
    std::set<int> grown = region;
    for (int v : region)
      for (int c : cells_of[v])
        for (int i = 0; i < node_count(mesh.types[c]); ++i) grown.insert(mesh.C(c, i));
    region.swap(grown);
  }
  std::vector<int> free_vertices;
  for (int v : region)
    if (!motion[v].isZero()) free_vertices.push_back(v);
  report.free_vertices = static_cast<int>(free_vertices.size());

  // Corners touching each free vertex (the vertex is the corner node or one of its three neighbours).
  std::vector<std::vector<Corner>> corners_of(nv);
  for (int v : free_vertices)
    for (int c : cells_of[v])
      for (int k = 0; k < node_count(mesh.types[c]); ++k) {
        const auto& n = corner_nodes(mesh.types[c], k);
        if (std::any_of(n.begin(), n.end(), [&](int local) { return mesh.C(c, local) == v; })) corners_of[v].push_back({c, k});
      }

  Energy energy;
  auto vertex_energy = [&](int v, Eigen::Vector3d* gradient) {
    double e = 0;
    if (gradient) gradient->setZero();
    for (const Corner& corner : corners_of[v]) {
      const CellType type = mesh.types[corner.cell];
      const CellNodes X = cell_nodes(mesh, corner.cell);
      const auto& n = corner_nodes(type, corner.k);
      Eigen::Matrix3d dA;
      e += energy.corner(corner_jacobian(type, X, corner.k), ideal_inverse(type, corner.k), gradient ? &dA : nullptr);
      if (!gradient) continue;
      // A = [x_a - x_k, x_b - x_k, x_c - x_k]: column j is +x_(n[j+1]) and -x_(n[0]).
      for (int j = 0; j < 3; ++j) {
        if (mesh.C(corner.cell, n[j + 1]) == v) *gradient += dA.col(j);
        if (mesh.C(corner.cell, n[0]) == v) *gradient -= dA.col(j);
      }
    }
    return e;
  };
  // delta from the worst corner determinant, relative to the typical corner size so it is scale free.
  auto update_delta = [&] {
    double sigma_min = std::numeric_limits<double>::infinity(), scale = 0;
    int count = 0;
    for (int v : free_vertices)
      for (const Corner& corner : corners_of[v]) {
        const CellType type = mesh.types[corner.cell];
        const Eigen::Matrix3d S =
            corner_jacobian(type, cell_nodes(mesh, corner.cell), corner.k) * ideal_inverse(type, corner.k);
        sigma_min = std::min(sigma_min, S.determinant());
        scale += std::abs(S.determinant());
        ++count;
      }
    const double eps = 1e-3 * scale / std::max(1, count);
    energy.delta2 = sigma_min < eps ? eps * (eps - sigma_min) : 0.0;
  };

  for (report.sweeps = 0; report.sweeps < options.max_sweeps; ++report.sweeps) {
    update_delta();
    double moved = 0, size = 0;
    for (int v : free_vertices) {
      Eigen::Vector3d g;
      const double e0 = vertex_energy(v, &g);
      g = motion[v] * g;  // allowed directions only
      if (!(g.norm() > 0) || !std::isfinite(e0)) continue;
      double edge = std::numeric_limits<double>::infinity();
      for (const Corner& corner : corners_of[v])
        for (int local : corner_nodes(mesh.types[corner.cell], corner.k))
          if (mesh.C(corner.cell, local) != v)
            edge = std::min(edge, (mesh.V.row(mesh.C(corner.cell, local)) - mesh.V.row(v)).norm());
      const Eigen::RowVector3d x0 = mesh.V.row(v);
      // Newton direction from a finite-difference Hessian of the analytic gradient, in the allowed subspace;
      // steepest descent where the Hessian is not positive definite.
      const double h = 1e-5 * edge;
      Eigen::Matrix3d H;
      for (int d = 0; d < 3; ++d) {
        Eigen::Vector3d gd;
        mesh.V(v, d) += h;
        vertex_energy(v, &gd);
        mesh.V(v, d) = x0(d);
        H.col(d) = (motion[v] * gd - g) / h;
      }
      H = 0.5 * (H + H.transpose()).eval();
      H = (motion[v] * H * motion[v]).eval() + (Eigen::Matrix3d::Identity() - motion[v]) * H.norm();
      Eigen::Vector3d step;
      const Eigen::LLT<Eigen::Matrix3d> llt(H);
      if (llt.info() == Eigen::Success && H.allFinite()) {
        step = -(motion[v] * llt.solve(g));
      } else {
        step = -g;
      }
      if (step.norm() > 0.5 * edge) step *= 0.5 * edge / step.norm();  // no jumps across several cells
      double t = 1;
      bool improved = false;
      for (int halving = 0; halving < 30 && !improved; ++halving, t *= 0.5) {
        mesh.V.row(v) = x0 + t * step.transpose();
        improved = vertex_energy(v, nullptr) < e0 + 1e-4 * t * g.dot(step);
      }
      if (!improved) mesh.V.row(v) = x0;
      moved = std::max(moved, (mesh.V.row(v) - x0).norm());
      size = std::max(size, edge);
    }
    int inverted = 0;
    for (int v : free_vertices)
      for (int c : cells_of[v]) inverted += min_corner_determinant(mesh.types[c], cell_nodes(mesh, c)) <= 0;
    if (inverted == 0 && moved < 1e-4 * size) break;
  }
  tally(report.inverted_after, report.bad_after, report.min_scaled_jacobian_after);
  return report;
}

}  // namespace facehex
