#include "core/segment/tragus.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <vector>

#include "core/segment/morphology.h"

namespace facehex {
namespace {

constexpr double kBandBelowPronasale = 25.0;  // mm: rule 5's band starts this far below the pronasale
constexpr double kBelowBand = 30.0;           // mm the levels reach below rule 5's band
constexpr double kWindowBack = 35.0;          // mm behind the ear's front: the concha's depth and more
constexpr double kWindowFront = 10.0;         // mm in front of the ear's front
constexpr double kClosingRadius = 9.0;        // mm: the disc bridges a concha 15 to 20 mm across
constexpr double kMinDepth = 5.0;             // mm the closing lies outside the reach in the hollow
constexpr double kMinMaxDepth = 8.0;          // mm: a hollow this deep somewhere (an ear's, not a skin fold's)
constexpr double kMinHollow = 300.0;          // mm^3: the sum of the hollow's depths over its area
constexpr double kDeepFraction = 0.5;         // of the hollow's greatest depth: its deep part
constexpr double kWallHeight = 5.0;           // mm the skin reaches further out in front of the wall
constexpr double kWallGap = 2.0;              // mm in front of the wall where it does
constexpr double kWallTolerance = 1.0;        // mm: walls this close to the most anterior one are the tragus's
// mm a tragus may lie behind the auricle's front edge: on the real CTs it lies 2-3 mm in front of it; a wall further
// back is one inside the concha, and the posterior cut would follow it.
constexpr double kMaxBehindAuricleEdge = 8.0;

// A map over the window's rows (j, along y) and levels (k, along z): a grid one voxel thick in x's place, so that the
// segmentation's grid tools (label_components) read it.
using Map = VoxelGrid<double>;

Map window_map(int rows, int levels, double dy, double dz) {
  GridGeometry g;
  g.dims = {rows, levels, 1};
  g.spacing = Eigen::Vector3d(dy, dz, 1);
  return Map(g, 0);
}

// Grey dilation (max) or erosion (min) by a disc of `radius` mm, the map extended by its border values.
Map grey(const Map& m, double radius, bool max) {
  const GridGeometry& g = m.geometry;
  const double dy = g.spacing.x(), dz = g.spacing.y();
  const int ry = static_cast<int>(radius / dy), rz = static_cast<int>(radius / dz);
  std::vector<std::pair<int, int>> disc;
  for (int b = -rz; b <= rz; ++b)
    for (int a = -ry; a <= ry; ++a)
      if ((a * dy) * (a * dy) + (b * dz) * (b * dz) <= radius * radius + 1e-9) disc.emplace_back(a, b);
  Map out(g, 0);
  for (int k = 0; k < g.dims[1]; ++k)
    for (int j = 0; j < g.dims[0]; ++j) {
      double best = max ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
      for (const auto& [a, b] : disc) {
        const double value = m(std::clamp(j + a, 0, g.dims[0] - 1), std::clamp(k + b, 0, g.dims[1] - 1), 0);
        best = max ? std::max(best, value) : std::min(best, value);
      }
      out(j, k, 0) = best;
    }
  return out;
}

std::optional<CtLandmark> find_tragus(const Mask& head, const FaceAnatomy& anatomy, int side) {
  const GridGeometry& g = head.geometry;
  const double front = anatomy.ear_fronts_y[side];
  if (!std::isfinite(front)) return std::nullopt;
  const auto index = [](double value, double origin, double spacing, int n) {
    return std::clamp(static_cast<int>(std::lround((value - origin) / spacing)), 0, n - 1);
  };
  const int j0 = index(front - kWindowBack, g.origin.y(), g.spacing.y(), g.dims[1]);
  const int j1 = index(front + kWindowFront, g.origin.y(), g.spacing.y(), g.dims[1]);
  const int k0 =
      index(anatomy.pronasale.z() - kBandBelowPronasale - kBelowBand, g.origin.z(), g.spacing.z(), g.dims[2]);
  const int k1 = index(anatomy.glabella.z(), g.origin.z(), g.spacing.z(), g.dims[2]);
  const int rows = j1 - j0 + 1, levels = k1 - k0 + 1;
  if (rows < 3 || levels < 3) return std::nullopt;

  // 1. The reach map.
  const double dy = g.spacing.y(), dz = g.spacing.z();
  Map reach = window_map(rows, levels, dy, dz);
  for (int k = 0; k < levels; ++k) {
    const double centre = anatomy.centre_at(g.point(0, 0, k0 + k).z());
    for (int j = 0; j < rows; ++j)
      for (int i = 0; i < g.dims[0]; ++i)
        if (head(i, j0 + j, k0 + k)) {
          const double out = side == 0 ? centre - g.point(i, 0, 0).x() : g.point(i, 0, 0).x() - centre;
          reach(j, k, 0) = std::max(reach(j, k, 0), out);
        }
  }
  // 2. The hollow.
  const Map closed = grey(grey(reach, kClosingRadius, true), kClosingRadius, false);
  Map depth = window_map(rows, levels, dy, dz);
  Mask deep(depth.geometry, 0);
  for (size_t p = 0; p < depth.data.size(); ++p) {
    depth.data[p] = reach.data[p] > 0 ? closed.data[p] - reach.data[p] : 0;
    deep.data[p] = depth.data[p] >= kMinDepth;
  }
  std::vector<int> label;  // 1..count, 0: not deep
  std::vector<size_t> sizes;
  const int count = label_components(deep, label, sizes);
  if (count == 0) return std::nullopt;
  std::vector<double> sum(count + 1, 0), deepest(count + 1, 0);
  for (size_t p = 0; p < label.size(); ++p)
    if (label[p] > 0)
      sum[label[p]] += depth.data[p] * dy * dz, deepest[label[p]] = std::max(deepest[label[p]], depth.data[p]);
  const int main = static_cast<int>(std::max_element(sum.begin() + 1, sum.end()) - sum.begin());
  if (sum[main] < kMinHollow || deepest[main] < kMinMaxDepth) return std::nullopt;
  Map in_main = window_map(rows, levels, dy, dz);
  for (size_t p = 0; p < label.size(); ++p) in_main.data[p] = label[p] == main ? 1 : 0;
  const Map near_main = grey(in_main, kClosingRadius, true);
  std::vector<bool> joined(count + 1, false);
  joined[main] = true;
  for (size_t p = 0; p < label.size(); ++p)
    if (label[p] > 0 && near_main.data[p] > 0 && deepest[label[p]] >= kMinMaxDepth) joined[label[p]] = true;
  const double greatest = deepest[main];

  // 3. The front wall per level.
  const int gap = std::max(1, static_cast<int>(std::lround(kWallGap / dy)));
  std::map<int, int> wall;  // level -> row
  for (int k = 0; k < levels; ++k)
    for (int j = rows - 1; j >= 0; --j) {
      const size_t p = depth.geometry.index(j, k, 0);
      if (!joined[label[p]] || depth.data[p] < kDeepFraction * greatest) continue;
      double ahead = -std::numeric_limits<double>::infinity();
      for (int a = 1; a <= gap && j + a < rows; ++a) ahead = std::max(ahead, reach(j + a, k, 0));
      if (ahead - reach(j, k, 0) >= kWallHeight) {
        wall[k] = j;
        break;
      }
    }
  if (wall.empty()) return std::nullopt;

  // 4. The tragus's levels and point.
  int most_anterior = -1;
  for (const auto& [k, j] : wall) most_anterior = std::max(most_anterior, j);
  int lowest = -1;
  for (const auto& [k, j] : wall)
    if (j == most_anterior) {
      lowest = k;
      break;
    }
  const int tolerance = static_cast<int>(std::lround(kWallTolerance / dy));
  const auto on_wall = [&](int k) {
    const auto it = wall.find(k);
    return it != wall.end() && it->second >= most_anterior - tolerance;
  };
  int first = lowest, last = lowest;
  while (on_wall(last + 1)) ++last;
  while (on_wall(first - 1)) --first;
  Eigen::Vector3d sum_point = Eigen::Vector3d::Zero();
  for (int k = first; k <= last; ++k) {
    const int j = wall.at(k);
    const double z = g.point(0, 0, k0 + k).z();
    const double centre = anatomy.centre_at(z);
    const double edge = reach(j + 1, k, 0);  // a wall has a row in front of it (step 3)
    sum_point += Eigen::Vector3d(side == 0 ? centre - edge : centre + edge, g.point(0, j0 + j, 0).y() + 0.5 * dy, z);
  }
  const Eigen::Vector3d point = sum_point / (last - first + 1);
  if (point.y() < front - kMaxBehindAuricleEdge) return std::nullopt;
  return CtLandmark{point, anatomy.ears_estimated};
}

}  // namespace

Tragi find_tragi(const Mask& head, const FaceAnatomy& anatomy) {
  return {find_tragus(head, anatomy, 0), find_tragus(head, anatomy, 1)};
}

}  // namespace facehex
