#include "core/segment/mouth_slit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "core/mesh/head_turn.h"
#include "core/segment/face_front.h"

namespace facehex {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Rule 1.
constexpr double kHalfWidth = 45;  // mm either side of the plane: past the widest adult mouth's corner
constexpr double kWindow = 15;     // mm above and below the stomion: the corners lie a few millimetres off its level
constexpr double kRayFront = 25;   // mm in front of the stomion where the rays start (in front of the lips)
constexpr double kRayBack = 50;    // mm behind it where they give up (behind the cheeks at the corners)
// Rule 2.
constexpr double kChord = 2;       // mm: half the chord; the slit is 1 to 2 mm tall, the lips' curves wider
constexpr double kColumnMean = 1;  // mm either side of a column
// Rule 3.
constexpr double kStep = 0.5;        // mm between the line's columns (the front's grid)
constexpr double kLevelStep = 0.25;  // mm between the levels the deepest notch is looked for at
constexpr double kReach = 0.5;       // mm in z the line may move between neighbouring columns: a mouth line's slope
// Rule 4.
constexpr double kDepthNear = 10;  // mm out: the slit's middle, between the philtrum's columns and the corners
constexpr double kMinDepth = 0.8;  // mm
// Rule 5.
constexpr double kCornerNear = 15;  // mm out: short of the narrowest adult mouth's corner (a width of 35 mm)
constexpr double kCornerFar = 42;   // mm out: beyond the widest's (85 mm)
constexpr int kMeanReach = 2;       // columns either side of one in the running mean: five columns, 2 mm
constexpr double kEndFraction = 0.5;
// Rule 6.
constexpr double kHeightBand = 3;  // mm
// The coarsest voxel the slit's end is read on.
constexpr double kMostSpacing = 1.5;  // mm
// An open mouth's corners.
constexpr double kOpenMargin = 5;    // mm above and below the labralia: the mouth line rises or falls to the corners
constexpr double kOpenEndDepth = 3;  // mm: more than closed lips' slit is deep

// The depth of an open mouth's gap in the column `x` of the front: over the heights z0 + k * kLevelStep up to z1, how
// far the front lies behind the lower of the lips' fronts above and below it, the deepest, and its height; a ray that
// meets nothing reaches `stop`.
std::pair<double, double> gap_depth(const FaceFront& front, double x, double z0, double z1, double stop) {
  std::vector<double> y;
  for (double z = z0; z <= z1 + 1e-9; z += kLevelStep) {
    const double at = front.mean_across(x, kColumnMean, z);
    y.push_back(std::isnan(at) ? stop : at);
  }
  const int n = static_cast<int>(y.size());
  std::vector<double> below(n), above(n);  // the most anterior front at or below, at or above each height
  for (int k = 0; k < n; ++k) below[k] = k == 0 ? y[0] : std::max(below[k - 1], y[k]);
  for (int k = n - 1; k >= 0; --k) above[k] = k == n - 1 ? y[k] : std::max(above[k + 1], y[k]);
  double deepest = 0, height = 0.5 * (z0 + z1);
  for (int k = 1; k + 1 < n; ++k) {
    const double d = std::min(below[k - 1], above[k + 1]) - y[k];
    if (d > deepest) deepest = d, height = z0 + k * kLevelStep;
  }
  return {deepest, height};
}

// The mean of depths[i] over the kMeanReach columns either side (fewer at the ends).
double running_mean(const std::vector<double>& depths, int i) {
  const int n = static_cast<int>(depths.size());
  double sum = 0;
  int count = 0;
  for (int k = std::max(0, i - kMeanReach); k <= std::min(n - 1, i + kMeanReach); ++k) sum += depths[k], ++count;
  return sum / count;
}

// Rule 5's end of a line: the first column i beyond kCornerNear (up to kCornerFar) whose running mean depth is below
// `end`, and how far (0-1) from column i - 1 towards i the mean crosses it; none where it does not.
std::optional<std::pair<int, double>> line_end(const std::vector<double>& offsets, const std::vector<double>& depths,
                                               double end) {
  const int n = static_cast<int>(offsets.size());
  for (int i = 1; i < n - kMeanReach; ++i) {
    if (offsets[i] < kCornerNear) continue;
    if (offsets[i] > kCornerFar) break;
    const double here = running_mean(depths, i);
    if (here >= end) continue;
    const double before = running_mean(depths, i - 1);
    return std::pair{i, before > here ? std::clamp((before - end) / (before - here), 0.0, 1.0) : 1.0};
  }
  return std::nullopt;
}

// One side's slit in the head frame: side -1 the right corner (-x), +1 the left.
class MouthSlit {
 public:
  MouthSlit(const FaceFront& front, double centre, double stomion_z, double lean, int side)
      : front_(front), centre_(centre), stomion_z_(stomion_z), rise_per_mm_(-lean * side), side_(side) {}

  std::optional<CtLandmark> corner() const {
    // Rule 3: the line, (offset, level above the stomion's line) column by column.
    std::vector<double> offsets, levels, depths;
    double level = 0;
    for (double offset = 0; offset <= kHalfWidth - kColumnMean + 1e-9; offset += kStep) {
      double best = kNaN, best_level = level;
      for (double l = level - kReach; l <= level + kReach + 1e-9; l += kLevelStep) {
        const double d = notch(offset, l);
        if (!std::isnan(d) && (std::isnan(best) || d > best)) best = d, best_level = l;
      }
      if (std::isnan(best)) break;
      level = std::clamp(best_level, -kWindow, kWindow);
      offsets.push_back(offset);
      levels.push_back(level);
      depths.push_back(best);
    }
    // Rule 4.
    std::vector<double> middle;
    for (size_t i = 0; i < offsets.size() && offsets[i] <= kDepthNear + 1e-9; ++i) middle.push_back(depths[i]);
    if (middle.empty()) return std::nullopt;
    std::nth_element(middle.begin(), middle.begin() + static_cast<long>(middle.size() / 2), middle.end());
    const double depth = middle[middle.size() / 2];
    if (depth < kMinDepth) return std::nullopt;
    // Rule 5.
    const auto crossing = line_end(offsets, depths, kEndFraction * depth);
    if (!crossing) return std::nullopt;
    const auto [i, t] = *crossing;
    const double offset = offsets[i - 1] + t * (offsets[i] - offsets[i - 1]);
    const double line_level = levels[i - 1] + t * (levels[i] - levels[i - 1]);
    return at_height(offset, steepest_level(offset, line_level));
  }

 private:
  double x_at(double offset) const { return centre_ + side_ * offset; }
  // The head frame's height of the level `level` above the stomion's line, `offset` mm out.
  double height(double offset, double level) const { return stomion_z_ + level + rise_per_mm_ * offset; }
  double front(double offset, double level) const { return front_(x_at(offset), height(offset, level)); }

  // Rule 2.
  double notch(double offset, double level) const {
    double sum = 0;
    int count = 0;
    for (double c = offset - kColumnMean; c <= offset + kColumnMean + 1e-9; c += kStep) {
      const double d = (front(c, level + kChord) + front(c, level - kChord)) / 2 - front(c, level);
      if (std::isnan(d)) return kNaN;
      sum += d;
      ++count;
    }
    return sum / count;
  }

  // Rule 6: the level within kHeightBand of `level` where dy/dz is largest, from differences a grid step apart.
  double steepest_level(double offset, double level) const {
    double best = -std::numeric_limits<double>::infinity(), best_level = level;
    for (double l = level - kHeightBand; l <= level + kHeightBand + 1e-9; l += kLevelStep) {
      const double slope = (front(offset, l + kLevelStep) - front(offset, l - kLevelStep)) / (2 * kLevelStep);
      if (!std::isnan(slope) && slope > best) best = slope, best_level = l;
    }
    return best_level;
  }

  std::optional<CtLandmark> at_height(double offset, double level) const {
    const double y = front(offset, level);
    if (std::isnan(y)) return std::nullopt;
    return CtLandmark{Eigen::Vector3d(x_at(offset), y, height(offset, level)), false};
  }

  const FaceFront& front_;
  double centre_, stomion_z_, rise_per_mm_;
  int side_;
};

}  // namespace

MouthCorners find_mouth_corners(const Field& ct, double skin_threshold, const MidSagittalPlane& plane,
                                const Eigen::Vector3d& stomion) {
  if (ct.geometry.spacing.maxCoeff() > kMostSpacing) return {};
  const HeadTurn frame = head_turn_of(plane);
  const Eigen::Vector3d s = frame.to_head(stomion);
  const MidSagittalPlane head_plane = frame.to_head(plane);
  const double centre = head_plane.x_at(s.y(), s.z());
  const double tilt = std::abs(head_plane.slope) * kHalfWidth;  // the most the levels rise or fall
  const double margin = kChord + kHeightBand + 1;
  const FaceFront front(ct, skin_threshold, frame, centre - kHalfWidth, centre + kHalfWidth,
                        s.z() - kWindow - margin - tilt, s.z() + kWindow + margin + tilt, s.y() + kRayFront,
                        s.y() - kRayBack);
  MouthCorners corners;
  for (const int side : {-1, 1}) {
    const std::optional<CtLandmark> corner = MouthSlit(front, centre, s.z(), head_plane.slope, side).corner();
    if (corner) corners[side < 0 ? 0 : 1] = CtLandmark{frame.to_model(corner->point), false};
  }
  return corners;
}

MouthCorners find_open_mouth_corners(const Field& ct, double skin_threshold, const MidSagittalPlane& plane,
                                     const Eigen::Vector3d& labrale_superius, const Eigen::Vector3d& labrale_inferius) {
  if (ct.geometry.spacing.maxCoeff() > kMostSpacing) return {};
  const HeadTurn frame = head_turn_of(plane);
  const Eigen::Vector3d top = frame.to_head(labrale_superius), bottom = frame.to_head(labrale_inferius);
  if (!(top.z() > bottom.z())) return {};
  const MidSagittalPlane head_plane = frame.to_head(plane);
  const double centre = head_plane.x_at(top.y(), 0.5 * (top.z() + bottom.z()));
  const double z0 = bottom.z() - kOpenMargin, z1 = top.z() + kOpenMargin;
  const double start = std::max(top.y(), bottom.y()) + kRayFront, stop = std::min(top.y(), bottom.y()) - kRayBack;
  const FaceFront front(ct, skin_threshold, frame, centre - kHalfWidth, centre + kHalfWidth, z0 - 1, z1 + 1, start,
                        stop);
  MouthCorners corners;
  for (const int side : {-1, 1}) {
    std::vector<double> offsets, depths, heights;
    for (double offset = 0; offset <= kHalfWidth - kColumnMean + 1e-9; offset += kStep) {
      const auto [depth, height] = gap_depth(front, centre + side * offset, z0, z1, stop);
      offsets.push_back(offset);
      depths.push_back(depth);
      heights.push_back(height);
    }
    // No gap between the plane and kCornerNear: the lips meet there, and no end of a gap is a corner.
    bool gap = false;
    for (size_t i = 0; i < offsets.size() && offsets[i] < kCornerNear; ++i)
      gap = gap || running_mean(depths, static_cast<int>(i)) >= kOpenEndDepth;
    const auto crossing = gap ? line_end(offsets, depths, kOpenEndDepth) : std::nullopt;
    if (!crossing) continue;
    const auto [i, t] = *crossing;
    const double x = centre + side * (offsets[i - 1] + t * (offsets[i] - offsets[i - 1])), z = heights[i - 1];
    // The lips' front across the gap: the more anterior of the fronts just above and below the deepest point.
    const double above = front(x, z + kOpenEndDepth), below = front(x, z - kOpenEndDepth);
    const double y = std::isnan(above) ? below : std::isnan(below) ? above : std::max(above, below);
    if (!std::isnan(y)) corners[side < 0 ? 0 : 1] = CtLandmark{frame.to_model(Eigen::Vector3d(x, y, z)), false};
  }
  return corners;
}

}  // namespace facehex
