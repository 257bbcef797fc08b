#include "core/correspondence/side_correspondence.h"

#include <algorithm>
#include <map>
#include <utility>

#include "core/mesh/tet_topology.h"
#include "core/quality/surface_distance.h"

namespace facehex {

Eigen::MatrixXi side_triangles(const Eigen::MatrixXi& T, const Eigen::VectorXi& side_mask, Side side) {
  const Eigen::MatrixXi F = boundary_faces(T).F;
  std::vector<int> rows;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    bool on = true;
    for (int k = 0; k < 3; ++k) on = on && (side_mask(F(f, k)) & side_bit(side));
    if (on) rows.push_back(static_cast<int>(f));
  }
  Eigen::MatrixXi out(static_cast<Eigen::Index>(rows.size()), 3);
  for (size_t i = 0; i < rows.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = F.row(rows[i]);
  return out;
}

SideCorrespondence side_correspondence(const Eigen::MatrixXd& standard_X, const Eigen::MatrixXi& standard_F,
                                       const Eigen::MatrixXd& standard_uvw, const Eigen::MatrixXd& patient_V,
                                       const Eigen::VectorXi& patient_mask, Side side) {
  SideCorrespondence c;
  for (int v = 0; v < patient_mask.size(); ++v)
    if (patient_mask(v) == side_bit(side)) c.vertices.push_back(v);
  const Eigen::MatrixXd P = patient_V(c.vertices, Eigen::all);
  const SurfaceLocator locator(standard_X, standard_F);
  const SurfaceLocator::Hits hits = locator.closest(P);
  c.uvw.resize(P.rows(), 3);
  c.distance = hits.distance;
  c.on_rim.assign(c.vertices.size(), 0);
  std::map<std::pair<int, int>, int> edge_uses;
  for (Eigen::Index f = 0; f < standard_F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = standard_F(f, k), b = standard_F(f, (k + 1) % 3);
      ++edge_uses[{std::min(a, b), std::max(a, b)}];
    }
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const Eigen::Vector3i f = standard_F.row(hits.face(i)).transpose();
    const Eigen::Vector3d w =
        triangle_barycentric(hits.point.row(i), standard_X.row(f(0)), standard_X.row(f(1)), standard_X.row(f(2)));
    c.uvw.row(i) = w(0) * standard_uvw.row(f(0)) + w(1) * standard_uvw.row(f(1)) + w(2) * standard_uvw.row(f(2));
    for (int k = 0; k < 3; ++k) {
      const int a = f((k + 1) % 3), b = f((k + 2) % 3);
      if (w(k) < 1e-9 && edge_uses[{std::min(a, b), std::max(a, b)}] == 1) c.on_rim[static_cast<size_t>(i)] = 1;
    }
  }
  return c;
}

}  // namespace facehex
