#include "core/segment/field_of_view.h"

#include <cmath>

namespace facehex {

bool ScanSides::outside(const Eigen::Vector3d& head_point) const {
  const Eigen::Vector3d p = turn.turned() ? turn.to_model(head_point) : head_point;
  return p.x() < lo.x() || p.x() > hi.x() || p.y() < lo.y() || p.y() > hi.y();
}

std::vector<FieldOfViewContact> field_of_view_contacts(const Mask& body, const ScanSides& scan, double z_lo,
                                                       double z_hi) {
  const GridGeometry& g = body.geometry;
  constexpr std::array<std::array<int, 2>, 3> kSteps = {{{-1, 0}, {1, 0}, {0, -1}}};  // ScanEdge's order
  std::vector<FieldOfViewContact> contacts;
  for (int k = 0; k < g.dims[2]; ++k) {
    const double z = g.point(0, 0, k).z();
    if (z < z_lo || z > z_hi) continue;
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        if (!body(i, j, k)) continue;
        for (int e = 0; e < 3; ++e) {
          const int ni = i + kSteps[e][0], nj = j + kSteps[e][1];
          // A body neighbour lies in the scan (the CT shows tissue there); one beyond the grid or of air may not.
          if (g.contains(ni, nj, k) && body(ni, nj, k)) continue;
          if (!scan.outside(g.point(ni, nj, k))) continue;
          contacts.push_back({g.point(i, j, k), static_cast<ScanEdge>(e)});
          break;
        }
      }
  }
  return contacts;
}

std::array<bool, 6> cut_grid_faces(const Mask& body, const std::vector<FieldOfViewContact>& contacts) {
  const GridGeometry& g = body.geometry;
  std::array<bool, 6> cut = {false, false, false, false, false, false};
  for (const FieldOfViewContact& c : contacts) {
    const Eigen::Vector3d at = (c.point - g.origin).cwiseQuotient(g.spacing);
    if (c.edge == ScanEdge::MinusX && std::lround(at.x()) == 0) cut[0] = true;
    if (c.edge == ScanEdge::PlusX && std::lround(at.x()) == g.dims[0] - 1) cut[1] = true;
    if (c.edge == ScanEdge::MinusY && std::lround(at.y()) == 0) cut[2] = true;
  }
  return cut;
}

}  // namespace facehex
