#include "core/mesh/hex_to_tets.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <vector>

#include "core/mesh/cell_faces.h"

namespace facehex {
namespace {

double signed_volume(const Eigen::MatrixXd& V, int a, int b, int c, int d) {
  const Eigen::Vector3d pa = V.row(a).transpose(), pb = V.row(b).transpose(), pc = V.row(c).transpose(),
                        pd = V.row(d).transpose();
  return (pb - pa).dot((pc - pa).cross(pd - pa)) / 6.0;
}

}  // namespace

AuxiliaryTets split_into_tets(const VolumeMesh& mesh) {
  std::vector<Eigen::Vector4i> tets;
  std::vector<int> parent;
  tets.reserve(static_cast<size_t>(mesh.num_cells()) * 6);
  for (int c = 0; c < mesh.num_cells(); ++c) {
    const auto row = mesh.C.row(c);
    if (mesh.types[c] == CellType::Tet) {
      tets.emplace_back(row(0), row(1), row(2), row(3));
      parent.push_back(c);
      continue;
    }
    int apex = row(0);
    for (int i = 1; i < node_count(mesh.types[c]); ++i) apex = std::min(apex, row(i));
    for (const LocalFace& face : cell_faces(mesh.types[c])) {
      const int n = face.size;
      int q[4] = {-1, -1, -1, -1};
      for (int k = 0; k < n; ++k) q[k] = row(face.node[k]);
      if (std::find(q, q + n, apex) != q + n) continue;
      if (n == 3) {
        tets.emplace_back(apex, q[0], q[1], q[2]);
      } else {
        const int s = static_cast<int>(std::min_element(q, q + 4) - q);  // diagonal through the smallest vertex
        const int a = q[s], b = q[(s + 1) % 4], d = q[(s + 2) % 4], e = q[(s + 3) % 4];
        tets.emplace_back(apex, a, b, d);
        tets.emplace_back(apex, a, d, e);
      }
      parent.insert(parent.end(), n == 3 ? 1 : 2, c);
    }
  }
  AuxiliaryTets out;
  out.T.resize(static_cast<Eigen::Index>(tets.size()), 4);
  out.parent = Eigen::Map<Eigen::VectorXi>(parent.data(), static_cast<Eigen::Index>(parent.size()));
  for (size_t t = 0; t < tets.size(); ++t) {
    out.T.row(static_cast<Eigen::Index>(t)) = tets[t].transpose();
    // Apex + an outward-oriented face triangle is positive; a non-positive volume means a badly shaped cell.
    if (signed_volume(mesh.V, tets[t](0), tets[t](1), tets[t](2), tets[t](3)) <= 0) ++out.non_positive_tets;
  }
  return out;
}

}  // namespace facehex
