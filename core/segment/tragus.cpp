#include "core/segment/tragus.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <vector>

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

// A 2D map over the window's rows (j) and levels (k), k slowest.
struct Map2 {
  int rows = 0, levels = 0;
  std::vector<double> v;
  Map2(int r, int l, double value) : rows(r), levels(l), v(static_cast<size_t>(r) * l, value) {}
  double& operator()(int j, int k) { return v[static_cast<size_t>(k) * rows + j]; }
  double operator()(int j, int k) const { return v[static_cast<size_t>(k) * rows + j]; }
};

// Grey dilation (max) or erosion (min) by a disc of `radius` mm, the map extended by its border values.
Map2 grey(const Map2& m, double radius, double dy, double dz, bool max) {
  const int ry = static_cast<int>(radius / dy), rz = static_cast<int>(radius / dz);
  std::vector<std::pair<int, int>> disc;
  for (int b = -rz; b <= rz; ++b)
    for (int a = -ry; a <= ry; ++a)
      if ((a * dy) * (a * dy) + (b * dz) * (b * dz) <= radius * radius + 1e-9) disc.emplace_back(a, b);
  Map2 out(m.rows, m.levels, 0);
  for (int k = 0; k < m.levels; ++k)
    for (int j = 0; j < m.rows; ++j) {
      double best = max ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
      for (const auto& [a, b] : disc) {
        const double value = m(std::clamp(j + a, 0, m.rows - 1), std::clamp(k + b, 0, m.levels - 1));
        best = max ? std::max(best, value) : std::min(best, value);
      }
      out(j, k) = best;
    }
  return out;
}

// 4-connected pieces of the pixels where `in` holds: a label per pixel (-1 outside) and the count.
int pieces(const std::vector<bool>& in, int rows, int levels, std::vector<int>& label) {
  label.assign(in.size(), -1);
  int count = 0;
  for (size_t start = 0; start < in.size(); ++start) {
    if (!in[start] || label[start] >= 0) continue;
    std::vector<size_t> stack = {start};
    label[start] = count;
    while (!stack.empty()) {
      const size_t p = stack.back();
      stack.pop_back();
      const int j = static_cast<int>(p % rows), k = static_cast<int>(p / rows);
      for (const auto& [a, b] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
        if (j + a < 0 || j + a >= rows || k + b < 0 || k + b >= levels) continue;
        const size_t q = static_cast<size_t>(k + b) * rows + (j + a);
        if (in[q] && label[q] < 0) label[q] = count, stack.push_back(q);
      }
    }
    ++count;
  }
  return count;
}

std::optional<Tragus> find_tragus(const Mask& head, const FaceAnatomy& anatomy, int side) {
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
  Map2 reach(rows, levels, 0);
  for (int k = 0; k < levels; ++k) {
    const double centre = anatomy.centre_at(g.point(0, 0, k0 + k).z());
    for (int j = 0; j < rows; ++j)
      for (int i = 0; i < g.dims[0]; ++i)
        if (head(i, j0 + j, k0 + k)) {
          const double out = side == 0 ? centre - g.point(i, 0, 0).x() : g.point(i, 0, 0).x() - centre;
          reach(j, k) = std::max(reach(j, k), out);
        }
  }
  // 2. The hollow.
  const double dy = g.spacing.y(), dz = g.spacing.z();
  const Map2 closed = grey(grey(reach, kClosingRadius, dy, dz, true), kClosingRadius, dy, dz, false);
  Map2 depth(rows, levels, 0);
  for (size_t p = 0; p < depth.v.size(); ++p) depth.v[p] = reach.v[p] > 0 ? closed.v[p] - reach.v[p] : 0;
  std::vector<bool> deep(depth.v.size());
  for (size_t p = 0; p < deep.size(); ++p) deep[p] = depth.v[p] >= kMinDepth;
  std::vector<int> label;
  const int count = pieces(deep, rows, levels, label);
  if (count == 0) return std::nullopt;
  std::vector<double> sum(count, 0), deepest(count, 0);
  for (size_t p = 0; p < label.size(); ++p)
    if (label[p] >= 0)
      sum[label[p]] += depth.v[p] * dy * dz, deepest[label[p]] = std::max(deepest[label[p]], depth.v[p]);
  const int main = static_cast<int>(std::max_element(sum.begin(), sum.end()) - sum.begin());
  if (sum[main] < kMinHollow || deepest[main] < kMinMaxDepth) return std::nullopt;
  Map2 in_main(rows, levels, 0);
  for (size_t p = 0; p < label.size(); ++p) in_main.v[p] = label[p] == main ? 1 : 0;
  const Map2 near_main = grey(in_main, kClosingRadius, dy, dz, true);
  std::vector<bool> joined(count, false);
  joined[main] = true;
  for (size_t p = 0; p < label.size(); ++p)
    if (label[p] >= 0 && near_main.v[p] > 0 && deepest[label[p]] >= kMinMaxDepth) joined[label[p]] = true;
  const double greatest = deepest[main];

  // 3. The front wall per level.
  const int gap = std::max(1, static_cast<int>(std::lround(kWallGap / dy)));
  std::map<int, int> wall;  // level -> row
  for (int k = 0; k < levels; ++k)
    for (int j = rows - 1; j >= 0; --j) {
      const size_t p = static_cast<size_t>(k) * rows + j;
      if (label[p] < 0 || !joined[label[p]] || depth.v[p] < kDeepFraction * greatest) continue;
      double ahead = -std::numeric_limits<double>::infinity();
      for (int a = 1; a <= gap && j + a < rows; ++a) ahead = std::max(ahead, reach(j + a, k));
      if (ahead - reach(j, k) >= kWallHeight) {
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
    return it != wall.end() && it->second >= most_anterior - tolerance && it->second + 1 < rows;
  };
  int first = lowest, last = lowest;
  while (on_wall(last + 1)) ++last;
  while (on_wall(first - 1)) --first;
  Eigen::Vector3d sum_point = Eigen::Vector3d::Zero();
  for (int k = first; k <= last; ++k) {
    const int j = wall.at(k);
    const double z = g.point(0, 0, k0 + k).z();
    const double centre = anatomy.centre_at(z);
    const double edge = reach(j + 1, k);
    sum_point += Eigen::Vector3d(side == 0 ? centre - edge : centre + edge, g.point(0, j0 + j, 0).y() + 0.5 * dy, z);
  }
  const Eigen::Vector3d point = sum_point / (last - first + 1);
  if (point.y() < front - kMaxBehindAuricleEdge) return std::nullopt;
  return Tragus{point, anatomy.ears_estimated};
}

}  // namespace

Tragi find_tragi(const Mask& head, const FaceAnatomy& anatomy) {
  return {find_tragus(head, anatomy, 0), find_tragus(head, anatomy, 1)};
}

}  // namespace facehex
