#include "core/segment/head_frame.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace facehex {

namespace {

// The bounding box of the box [lo, hi] turned into the head frame.
std::pair<Eigen::Vector3d, Eigen::Vector3d> turned_box(const HeadTurn& turn, const Eigen::Vector3d& lo,
                                                       const Eigen::Vector3d& hi) {
  Eigen::Vector3d out_lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), out_hi = -out_lo;
  for (const double x : {lo.x(), hi.x()})
    for (const double y : {lo.y(), hi.y()})
      for (const double z : {lo.z(), hi.z()}) {
        const Eigen::Vector3d p = turn.to_head(Eigen::Vector3d(x, y, z));
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
  const Eigen::Vector3d field_lo(g.lower(0), g.lower(1), g.lower(2)), field_hi(g.upper(0), g.upper(1), g.upper(2));
  const auto [lo, hi] = turned_box(turn, field_lo, field_hi);
  const auto [region_head_lo, region_head_hi] =
      turned_box(turn, Eigen::Vector3d(region_lo.x(), region_lo.y(), g.lower(2)),
                 Eigen::Vector3d(region_hi.x(), region_hi.y(), g.upper(2)));
  GridGeometry target;
  target.spacing = Eigen::Vector3d::Constant(spacing);
  for (int a = 0; a < 3; ++a) {
    // The whole turned box's voxels lo(a) + i * spacing, those within the turned region.
    const int all = static_cast<int>(std::floor((hi(a) - lo(a)) / spacing + 1e-9)) + 1;
    const int first = std::clamp(static_cast<int>(std::floor((region_head_lo(a) - lo(a)) / spacing)), 0, all - 1);
    const int last = std::clamp(static_cast<int>(std::ceil((region_head_hi(a) - lo(a)) / spacing)), first, all - 1);
    target.origin(a) = lo(a) + first * spacing;
    target.dims[a] = last - first + 1;
  }
  const ModelFromHead to_model(turn);
  return resample_mapped(
      field, target, [&to_model](const Eigen::Vector3d& p) { return to_model(p); }, outside);
}

}  // namespace facehex
