#include "core/segment/head_frame.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace facehex {

namespace {

// The bounding box of the x-y box [lo, hi] turned into the head frame.
std::pair<Eigen::Vector2d, Eigen::Vector2d> turned_box(const HeadTurn& turn, const Eigen::Vector2d& lo,
                                                       const Eigen::Vector2d& hi) {
  Eigen::Vector2d out_lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), out_hi = -out_lo;
  for (const double x : {lo.x(), hi.x()})
    for (const double y : {lo.y(), hi.y()}) {
      const Eigen::Vector2d p = turn.to_head(Eigen::Vector3d(x, y, 0)).head<2>();
      out_lo = out_lo.cwiseMin(p);
      out_hi = out_hi.cwiseMax(p);
    }
  return {out_lo, out_hi};
}

}  // namespace

Field turned_to_head_frame(const Field& field, const HeadTurn& turn, double spacing, float outside) {
  const GridGeometry& g = field.geometry;
  return turned_to_head_frame(field, turn, spacing, outside, Eigen::Vector2d(g.lower(0), g.lower(1)),
                              Eigen::Vector2d(g.upper(0), g.upper(1)));
}

Field turned_to_head_frame(const Field& field, const HeadTurn& turn, double spacing, float outside,
                           const Eigen::Vector2d& region_lo, const Eigen::Vector2d& region_hi) {
  const GridGeometry& g = field.geometry;
  const auto [lo, hi] =
      turned_box(turn, Eigen::Vector2d(g.lower(0), g.lower(1)), Eigen::Vector2d(g.upper(0), g.upper(1)));
  const auto [region_head_lo, region_head_hi] = turned_box(turn, region_lo, region_hi);
  GridGeometry target;
  target.spacing = Eigen::Vector3d::Constant(spacing);
  target.origin = Eigen::Vector3d(lo.x(), lo.y(), g.lower(2));
  target.dims[2] = static_cast<int>(std::floor((g.upper(2) - g.lower(2)) / spacing + 1e-9)) + 1;
  for (int a = 0; a < 2; ++a) {
    // The whole turned box's voxels lo(a) + i * spacing, those within the turned region.
    const int all = static_cast<int>(std::floor((hi(a) - lo(a)) / spacing + 1e-9)) + 1;
    const int first = std::clamp(static_cast<int>(std::floor((region_head_lo(a) - lo(a)) / spacing)), 0, all - 1);
    const int last = std::clamp(static_cast<int>(std::ceil((region_head_hi(a) - lo(a)) / spacing)), first, all - 1);
    target.origin(a) = lo(a) + first * spacing;
    target.dims[a] = last - first + 1;
  }
  return resample_mapped(
      field, target, [&turn](const Eigen::Vector3d& p) { return turn.to_model(p); }, outside);
}

}  // namespace facehex
