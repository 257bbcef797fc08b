#include "core/evaluation/standard_remesh.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <random>

#include "core/fields/tet_domain.h"
#include "core/mesh/cell_faces.h"
#include "core/mesh/hex_to_tets.h"
#include "core/mesh/sides.h"
#include "core/mesh/tet_topology.h"
#include "core/segment/remesh.h"
#include "core/standard/closed_domain.h"
#include "core/tetgen/tetrahedralize.h"

namespace facehex {
namespace {

VolumeMesh with_sides(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, const Eigen::VectorXi& side_mask) {
  VolumeMesh m = VolumeMesh::from_tets(V, T);
  m.point_data[kSideMaskArray] = side_mask.cast<double>();
  return m;
}

}  // namespace

VolumeMesh split_hex_model(const VolumeMesh& standard) {
  const AuxiliaryTets aux = split_into_tets(standard);
  const TetDomain d = auxiliary_domain(standard);
  std::vector<char> bad(static_cast<size_t>(standard.num_cells()), 0);
  for (Eigen::Index t = 0; t < aux.T.rows(); ++t) {
    Eigen::Vector3d e[3];
    for (int k = 0; k < 3; ++k) e[k] = (d.V.row(aux.T(t, k + 1)) - d.V.row(aux.T(t, 0))).transpose();
    if (e[0].cross(e[1]).dot(e[2]) <= 0) bad[aux.parent(t)] = 1;
  }
  // Bad cells and their face neighbours are split as cones; the bad cells' quads through their centres.
  const FaceNeighbors neighbors = face_neighbors(standard);
  std::vector<char> cone = bad;
  for (int c = 0; c < standard.num_cells(); ++c)
    if (bad[c])
      for (const auto& [n, f] : neighbors[c])
        if (n >= 0) cone[n] = 1;
  std::vector<Eigen::RowVector3d> added;
  std::vector<int> added_mask;
  std::map<std::vector<int>, int> quad_centre;  // sorted corners -> vertex id
  for (int c = 0; c < standard.num_cells(); ++c) {
    if (!bad[c]) continue;
    for (size_t f = 0; f < cell_faces(standard.types[c]).size(); ++f) {
      std::vector<int> q = face_vertices(standard, c, static_cast<int>(f));
      if (q.size() != 4) continue;
      std::vector<int> key = q;
      std::sort(key.begin(), key.end());
      if (quad_centre.count(key)) continue;
      Eigen::RowVector3d p = Eigen::RowVector3d::Zero();
      int common = ~0;
      for (const int v : q) {
        p += d.V.row(v) / 4.0;
        common &= d.side_mask.size() ? d.side_mask(v) : 0;
      }
      quad_centre[key] = static_cast<int>(d.V.rows() + static_cast<Eigen::Index>(added.size()));
      added.push_back(p);
      added_mask.push_back(neighbors[c][f][0] < 0 ? common : 0);
    }
  }
  Eigen::MatrixXd V(d.V.rows() + static_cast<Eigen::Index>(added.size()), 3);
  V.topRows(d.V.rows()) = d.V;
  for (size_t i = 0; i < added.size(); ++i) V.row(d.V.rows() + static_cast<Eigen::Index>(i)) = added[i];
  std::vector<Eigen::Vector4i> tets;
  for (Eigen::Index t = 0; t < aux.T.rows(); ++t)
    if (!cone[aux.parent(t)]) tets.emplace_back(aux.T.row(t).transpose());
  std::vector<Eigen::RowVector3d> apexes;
  for (int c = 0; c < standard.num_cells(); ++c) {
    if (!cone[c]) continue;
    std::vector<std::array<int, 3>> triangles;  // outward
    for (size_t f = 0; f < cell_faces(standard.types[c]).size(); ++f) {
      std::vector<int> q = face_vertices(standard, c, static_cast<int>(f));
      std::vector<int> key = q;
      std::sort(key.begin(), key.end());
      const auto centre = q.size() == 4 ? quad_centre.find(key) : quad_centre.end();
      if (centre != quad_centre.end()) {
        for (int k = 0; k < 4; ++k) triangles.push_back({q[k], q[(k + 1) % 4], centre->second});
        continue;
      }
      if (q.size() == 4) std::rotate(q.begin(), std::min_element(q.begin(), q.end()), q.end());  // as hex_to_tets
      for (size_t k = 1; k + 1 < q.size(); ++k) triangles.push_back({q[0], q[k], q[k + 1]});
    }
    // The apex: the cell's centre, else a convex combination of its corners that sees every face triangle from
    // inside (a reproducible search).
    const auto smallest_volume = [&](const Eigen::Vector3d& apex) {
      double lowest = std::numeric_limits<double>::infinity();
      for (const auto& t : triangles) {
        const Eigen::Vector3d a = V.row(t[0]).transpose(), b = V.row(t[1]).transpose(), e = V.row(t[2]).transpose();
        lowest = std::min(lowest, (e - a).cross(b - a).dot(apex - a));  // apex inside: positive
      }
      return lowest;
    };
    const int n = node_count(standard.types[c]);
    Eigen::Vector3d best = Eigen::Vector3d::Zero();
    for (int k = 0; k < n; ++k) best += standard.V.row(standard.C(c, k)).transpose() / n;
    std::mt19937 rng(static_cast<unsigned>(c));
    for (int trial = 0; smallest_volume(best) <= 0 && trial < 4000; ++trial) {
      Eigen::VectorXd w(n);
      for (int k = 0; k < n; ++k) w(k) = 1e-3 + static_cast<double>(rng() % 1000);
      Eigen::Vector3d candidate = Eigen::Vector3d::Zero();
      for (int k = 0; k < n; ++k) candidate += w(k) / w.sum() * standard.V.row(standard.C(c, k)).transpose();
      if (smallest_volume(candidate) > 0) best = candidate;
    }
    const int apex = static_cast<int>(V.rows() + static_cast<Eigen::Index>(apexes.size()));
    apexes.push_back(best.transpose());
    for (const auto& t : triangles) tets.emplace_back(t[0], t[2], t[1], apex);
  }
  const Eigen::Index before = V.rows();
  V.conservativeResize(before + static_cast<Eigen::Index>(apexes.size()), 3);
  for (size_t i = 0; i < apexes.size(); ++i) V.row(before + static_cast<Eigen::Index>(i)) = apexes[i];
  Eigen::VectorXi side_mask = Eigen::VectorXi::Zero(V.rows());
  side_mask.head(d.side_mask.size()) = d.side_mask;
  for (size_t i = 0; i < added_mask.size(); ++i) side_mask(d.V.rows() + static_cast<Eigen::Index>(i)) = added_mask[i];
  Eigen::MatrixXi T(static_cast<Eigen::Index>(tets.size()), 4);
  for (Eigen::Index i = 0; i < T.rows(); ++i) T.row(i) = tets[i].transpose();
  return with_sides(V, T, side_mask);
}

VolumeMesh tetgen_remesh(const VolumeMesh& standard, bool closed, double edge_length) {
  const TetDomain d = closed ? closed_domain(standard) : auxiliary_domain(standard);
  TetrahedralizeOptions options;
  options.target_edge_length = edge_length;
  return tetrahedralize_with_sides(remesh_isotropic(domain_surface(d), edge_length), options).mesh;
}

}  // namespace facehex
