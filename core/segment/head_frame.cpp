#include "core/segment/head_frame.h"

#include <cmath>
#include <limits>

namespace facehex {

Field turned_to_head_frame(const Field& field, const HeadTurn& turn, double spacing, float outside) {
  const GridGeometry& g = field.geometry;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const double x : {g.lower(0), g.upper(0)})
    for (const double y : {g.lower(1), g.upper(1)}) {
      const Eigen::Vector3d p = turn.to_head(Eigen::Vector3d(x, y, 0));
      lo = lo.cwiseMin(p.head<2>());
      hi = hi.cwiseMax(p.head<2>());
    }
  GridGeometry target;
  target.spacing = Eigen::Vector3d::Constant(spacing);
  target.origin = Eigen::Vector3d(lo.x(), lo.y(), g.lower(2));
  for (int a = 0; a < 3; ++a)
    target.dims[a] =
        static_cast<int>(std::floor((a < 2 ? hi(a) - lo(a) : g.upper(2) - g.lower(2)) / spacing + 1e-9)) + 1;
  return resample_mapped(
      field, target, [&turn](const Eigen::Vector3d& p) { return turn.to_model(p); }, outside);
}

}  // namespace facehex
