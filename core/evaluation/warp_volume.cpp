#include "core/evaluation/warp_volume.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/segment/thresholds.h"
#include "core/util/error.h"

namespace facehex {

Field warp_volume(const Field& field, const SmoothWarp& warp) {
  const GridGeometry& g = field.geometry;
  // The image of the original box's boundary bounds the image of the box (W is a homeomorphism); across, its faces
  // sampled every 4 voxels with a margin of 2.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (int a = 0; a < 3; ++a)
    for (const int side : {0, g.dims[a] - 1}) {
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      for (int i = 0; i < g.dims[b]; i += 4)
        for (int j = 0; j < g.dims[c]; j += 4) {
          Eigen::Vector3i ijk;
          ijk(a) = side;
          ijk(b) = i;
          ijk(c) = j;
          const Eigen::Vector3d y = warp.apply(g.point(ijk(0), ijk(1), ijk(2)));
          lo = lo.cwiseMin(y);
          hi = hi.cwiseMax(y);
        }
    }
  lo -= 2 * g.spacing;
  hi += 2 * g.spacing;
  // A scanner's volume ends in slice planes; W may bend the original's: the slices are cropped to those the original
  // covers across their whole area, between the highest level of the bottom slice's image and the lowest of the top
  // slice's (every voxel of both: a warp that keeps them flat keeps all of the original's levels). A pitched or rolled
  // warp tilts them across the whole scan, and such a crop would cut the face; it keeps the whole image, as a head
  // pitched or tilted within a scanner's taller field of view, with air beyond the original's tilted end slices.
  if (!warp.tilts_slices()) {
    double top_lowest = std::numeric_limits<double>::infinity(), bottom_highest = -top_lowest;
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        bottom_highest = std::max(bottom_highest, warp.apply(g.point(i, j, 0)).z());
        top_lowest = std::min(top_lowest, warp.apply(g.point(i, j, g.dims[2] - 1)).z());
      }
    lo.z() = bottom_highest;
    hi.z() = top_lowest;
  }
  GridGeometry target;
  target.spacing = g.spacing;
  target.origin = lo;
  for (int a = 0; a < 2; ++a) target.dims[a] = static_cast<int>(std::ceil((hi(a) - lo(a)) / g.spacing(a))) + 1;
  target.dims[2] = static_cast<int>(std::floor((hi.z() - lo.z()) / g.spacing.z() + 1e-9)) + 1;  // not beyond the top
  const float air = *std::min_element(field.data.begin(), field.data.end());
  return resample_mapped(
      field, target, [&warp](const Eigen::Vector3d& y) { return warp.inverse(y); }, air);
}

CtWarpFrame ct_warp_frame(const Field& intensity) {
  const GridGeometry& g = intensity.geometry;
  const double skin = estimate_thresholds(intensity).skin;
  std::vector<Eigen::Vector3d> front;  // per column (i, k) with tissue, its most anterior tissue voxel
  double most_anterior = -std::numeric_limits<double>::infinity();
  for (int k = 0; k < g.dims[2]; ++k)
    for (int i = 0; i < g.dims[0]; ++i)
      for (int j = g.dims[1] - 1; j >= 0; --j)
        if (intensity(i, j, k) >= skin) {
          front.push_back(g.point(i, j, k));
          most_anterior = std::max(most_anterior, front.back().y());
          break;
        }
  if (front.empty()) throw Error("benchmark", "the CT has no voxel above its skin threshold to draw warps about");
  CtWarpFrame frame;
  std::vector<Eigen::Vector3d> kept;
  for (const Eigen::Vector3d& p : front)
    if (p.y() >= most_anterior - kWarpFrameDepth) kept.push_back(p);
  frame.anchors.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (size_t r = 0; r < kept.size(); ++r) frame.anchors.row(static_cast<Eigen::Index>(r)) = kept[r].transpose();
  frame.centre = frame.anchors.colwise().mean().transpose();
  return frame;
}

}  // namespace facehex
