#include "core/standard/closed_domain.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <utility>

#include "core/mesh/sides.h"
#include "core/mesh/tet_topology.h"
#include "core/tetgen/tetrahedralize.h"
#include "core/util/error.h"

namespace facehex {
namespace {

using Edge = std::pair<int, int>;
Edge edge(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

// Connected components (through shared edges) of a set of triangles; returns the component of each.
std::vector<int> triangle_components(const std::vector<Eigen::Vector3i>& tris, int& count) {
  std::map<Edge, std::vector<int>> by_edge;
  for (size_t i = 0; i < tris.size(); ++i)
    for (int k = 0; k < 3; ++k) by_edge[edge(tris[i](k), tris[i]((k + 1) % 3))].push_back(static_cast<int>(i));
  std::vector<int> comp(tris.size(), -1);
  count = 0;
  for (size_t seed = 0; seed < tris.size(); ++seed) {
    if (comp[seed] >= 0) continue;
    std::vector<int> stack = {static_cast<int>(seed)};
    comp[seed] = count;
    while (!stack.empty()) {
      const int t = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k)
        for (int n : by_edge[edge(tris[t](k), tris[t]((k + 1) % 3))])
          if (comp[n] < 0) {
            comp[n] = count;
            stack.push_back(n);
          }
    }
    ++count;
  }
  return comp;
}

// The closed vertex loops bounding a set of triangles (edges used once). Empty if the rim is not a set of simple
// loops (a vertex with more than two rim edges).
std::vector<std::vector<int>> rim_loops(const std::vector<Eigen::Vector3i>& tris) {
  std::map<Edge, int> uses;
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k) ++uses[edge(t(k), t((k + 1) % 3))];
  std::map<int, std::vector<int>> next;
  for (const auto& [e, n] : uses)
    if (n == 1) {
      next[e.first].push_back(e.second);
      next[e.second].push_back(e.first);
    }
  for (const auto& [v, n] : next)
    if (n.size() != 2) return {};
  std::vector<std::vector<int>> loops;
  std::set<int> seen;
  for (const auto& [start, n] : next) {
    if (seen.count(start)) continue;
    std::vector<int> loop = {start};
    seen.insert(start);
    int prev = start, cur = n[0];
    while (cur != start) {
      loop.push_back(cur);
      seen.insert(cur);
      const auto& nb = next[cur];
      const int step = nb[0] == prev ? nb[1] : nb[0];
      prev = cur;
      cur = step;
    }
    loops.push_back(loop);
  }
  return loops;
}

// A triangulation of a closed loop of vertices of least total area (dynamic programming over sub-polygons, as in
// hole filling), which follows non-planar rims such as the lips better than a planar projection.
std::vector<Eigen::Vector3i> cap_loop(const Eigen::MatrixXd& V, const std::vector<int>& loop) {
  const int n = static_cast<int>(loop.size());
  if (n < 3) return {};
  auto area = [&](int i, int j, int k) {
    const Eigen::Vector3d a = V.row(loop[i]).transpose(), b = V.row(loop[j]).transpose(),
                          c = V.row(loop[k]).transpose();
    return 0.5 * (b - a).cross(c - a).norm();
  };
  std::vector<std::vector<double>> best(n, std::vector<double>(n, 0.0));
  std::vector<std::vector<int>> split(n, std::vector<int>(n, -1));
  for (int gap = 2; gap < n; ++gap)
    for (int i = 0; i + gap < n; ++i) {
      const int j = i + gap;
      best[i][j] = std::numeric_limits<double>::infinity();
      for (int m = i + 1; m < j; ++m) {
        const double a = best[i][m] + best[m][j] + area(i, m, j);
        if (a < best[i][j]) {
          best[i][j] = a;
          split[i][j] = m;
        }
      }
    }
  std::vector<Eigen::Vector3i> tris;
  std::vector<std::pair<int, int>> stack = {{0, n - 1}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j - i < 2) continue;
    const int m = split[i][j];
    tris.emplace_back(loop[i], loop[m], loop[j]);
    stack.push_back({i, m});
    stack.push_back({m, j});
  }
  return tris;
}

// Orients cap triangles against the wall triangles they close: a rim edge a->b of a wall triangle must appear as
// b->a in the cap (one consistently oriented closed surface).
void orient_cap(std::vector<Eigen::Vector3i>& cap, const std::vector<Eigen::Vector3i>& walls) {
  std::set<Edge> wall_directed;
  for (const auto& t : walls)
    for (int k = 0; k < 3; ++k) wall_directed.insert({t(k), t((k + 1) % 3)});
  for (const auto& t : cap)
    for (int k = 0; k < 3; ++k) {
      const Edge e = {t(k), t((k + 1) % 3)};
      if (wall_directed.count(e)) {  // same direction as the wall: the cap is reversed
        for (auto& c : cap) std::swap(c(1), c(2));
        return;
      }
      if (wall_directed.count({e.second, e.first})) return;
    }
}

}  // namespace

TetDomain closed_domain(const VolumeMesh& hex) {
  TetDomain d = auxiliary_domain(hex);
  if (d.side_mask.size() != d.V.rows())
    throw Error("closed domain", "the standard has no \"side_mask\" (label its sides first: facehex sides)");
  return close_openings(std::move(d), "auxiliary tets");
}

std::vector<std::vector<Eigen::Vector3i>> sideless_boundary_pieces(const TetDomain& d) {
  const BoundaryFaces boundary = boundary_faces(d.T);
  std::vector<Eigen::Vector3i> sideless;
  for (int f = 0; f < boundary.F.rows(); ++f) {
    const Eigen::Vector3i t = boundary.F.row(f).transpose();
    if ((d.side_mask(t(0)) & d.side_mask(t(1)) & d.side_mask(t(2))) == 0) sideless.push_back(t);
  }
  int count = 0;
  const std::vector<int> piece = triangle_components(sideless, count);
  std::vector<std::vector<Eigen::Vector3i>> pieces(static_cast<size_t>(count));
  for (size_t i = 0; i < sideless.size(); ++i) pieces[piece[i]].push_back(sideless[i]);
  return pieces;
}

TetDomain close_openings(TetDomain d, const std::string& kind) {
  if (d.side_mask.size() != d.V.rows()) return d;
  int openings = 0, closed = 0;
  std::vector<Eigen::Vector4i> new_tets;
  std::vector<Eigen::RowVector3d> new_points;
  for (std::vector<Eigen::Vector3i>& plug : sideless_boundary_pieces(d)) {
    bool sideless_vertex = false;
    for (const Eigen::Vector3i& t : plug)
      for (int k = 0; k < 3; ++k) sideless_vertex |= d.side_mask(t(k)) == 0;
    if (!sideless_vertex) continue;  // where sides meet, not an opening
    const std::vector<Eigen::Vector3i> wall = plug;
    const std::vector<std::vector<int>> loops = rim_loops(wall);
    if (loops.size() < 2) continue;  // a dent in one side, not an opening through the shell
    ++openings;
    double wall_edges = 0;
    for (const auto& t : plug) wall_edges += (d.V.row(t(0)) - d.V.row(t(1))).norm();
    bool capped = true;
    for (const auto& loop : loops) {
      auto cap = cap_loop(d.V, loop);
      capped = capped && !cap.empty();
      orient_cap(cap, wall);
      plug.insert(plug.end(), cap.begin(), cap.end());
    }
    // The walls face out of the standard, i.e. into the plug: reverse everything so the plug's surface faces out.
    for (auto& t : plug) std::swap(t(1), t(2));
    if (!capped || plug.empty()) continue;
    // The plug's closed surface, on local vertex ids.
    std::map<int, int> local;
    std::vector<int> global;
    SurfaceMesh surface;
    surface.F.resize(static_cast<Eigen::Index>(plug.size()), 3);
    for (size_t i = 0; i < plug.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        const auto [it, inserted] = local.emplace(plug[i](k), static_cast<int>(global.size()));
        if (inserted) global.push_back(plug[i](k));
        surface.F(static_cast<Eigen::Index>(i), k) = it->second;
      }
    surface.V.resize(static_cast<Eigen::Index>(global.size()), 3);
    for (size_t i = 0; i < global.size(); ++i) surface.V.row(static_cast<Eigen::Index>(i)) = d.V.row(global[i]);
    TetrahedralizeOptions options;
    options.preserve_surface = true;
    options.target_edge_length = wall_edges / static_cast<double>(plug.size());
    TetrahedralizeResult plug_mesh;
    try {
      plug_mesh = tetrahedralize(surface, options);
    } catch (const Error&) {
      continue;  // this opening stays open (reported in the description)
    }
    // TetGen may renumber the surface points: match them by their (exact) coordinates; the rest are new.
    const Eigen::MatrixXd& PV = plug_mesh.mesh.V;
    std::map<std::array<double, 3>, int> surface_point;
    for (Eigen::Index i = 0; i < surface.V.rows(); ++i)
      surface_point[{surface.V(i, 0), surface.V(i, 1), surface.V(i, 2)}] = global[i];
    std::vector<int> to_global(PV.rows());
    for (Eigen::Index i = 0; i < PV.rows(); ++i) {
      const auto it = surface_point.find({PV(i, 0), PV(i, 1), PV(i, 2)});
      if (it != surface_point.end()) {
        to_global[i] = it->second;
      } else {
        to_global[i] = static_cast<int>(d.V.rows() + new_points.size());
        new_points.push_back(PV.row(i));
      }
    }
    const Eigen::MatrixXi PT = plug_mesh.mesh.tets();
    for (Eigen::Index t = 0; t < PT.rows(); ++t)
      new_tets.emplace_back(to_global[PT(t, 0)], to_global[PT(t, 1)], to_global[PT(t, 2)], to_global[PT(t, 3)]);
    ++closed;
  }
  const Eigen::Index nv = d.V.rows(), nt = d.T.rows();
  d.V.conservativeResize(nv + static_cast<Eigen::Index>(new_points.size()), 3);
  for (size_t i = 0; i < new_points.size(); ++i) d.V.row(nv + static_cast<Eigen::Index>(i)) = new_points[i];
  d.side_mask.conservativeResize(d.V.rows());
  d.side_mask.tail(static_cast<Eigen::Index>(new_points.size())).setZero();  // plug interiors lie on no side
  d.T.conservativeResize(nt + static_cast<Eigen::Index>(new_tets.size()), 4);
  for (size_t i = 0; i < new_tets.size(); ++i) d.T.row(nt + static_cast<Eigen::Index>(i)) = new_tets[i].transpose();
  d.closed_openings = closed;
  d.description = kind + (openings == 0 ? std::string(", no opening")
                                        : " with " + std::to_string(closed) + " of " + std::to_string(openings) +
                                              " openings closed by TetGen plugs");
  return d;
}

SurfaceMesh domain_surface(const TetDomain& d) {
  const BoundaryFaces b = boundary_faces(d.T);
  Eigen::VectorXi index = Eigen::VectorXi::Constant(d.V.rows(), -1);
  SurfaceMesh s;
  s.F.resize(b.F.rows(), 3);
  s.labels.setZero(b.F.rows());
  int used = 0;
  for (Eigen::Index f = 0; f < b.F.rows(); ++f) {
    int common = ~0;
    for (int k = 0; k < 3; ++k) {
      const int v = b.F(f, k);
      if (index(v) < 0) index(v) = used++;
      s.F(f, k) = index(v);
      common &= d.side_mask.size() ? d.side_mask(v) : 0;
    }
    for (int side = 0; side < kNumSides; ++side)
      if (common & (1 << side)) {
        s.labels(f) = side + 1;
        break;
      }
  }
  s.V.resize(used, 3);
  for (Eigen::Index v = 0; v < d.V.rows(); ++v)
    if (index(v) >= 0) s.V.row(index(v)) = d.V.row(v);
  return s;
}

std::vector<std::vector<int>> opening_rims(const TetDomain& domain,
                                           const std::vector<std::vector<Eigen::Vector3i>>& pieces, int side_bits) {
  std::vector<std::vector<int>> rims(pieces.size());
  for (size_t o = 0; o < pieces.size(); ++o) {
    for (const Eigen::Vector3i& t : pieces[o])
      for (int k = 0; k < 3; ++k)
        if (domain.side_mask(t(k)) & side_bits) rims[o].push_back(t(k));
    std::sort(rims[o].begin(), rims[o].end());
    rims[o].erase(std::unique(rims[o].begin(), rims[o].end()), rims[o].end());
  }
  return rims;
}

}  // namespace facehex
