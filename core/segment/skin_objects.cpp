#include "core/segment/skin_objects.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/mesh/head_turn.h"
#include "core/segment/face_front.h"

namespace facehex {
namespace {

constexpr double kProfileHalfWidth = 2;  // mm either side of the plane: a column's noise averaged
constexpr double kStep = 0.25;           // mm between the profile's points
// mm above the nose tip: where the profile starts, above the tip's bulb, whose dorsum bends sharply
constexpr double kAbovePronasale = 15;
constexpr double kReach = 110;      // mm above the nose tip: the forehead up to about the hairline
constexpr double kRayFront = 10;    // mm in front of the nose tip where the rays start
constexpr double kRayBack = 80;     // mm behind it where they give up
constexpr double kMinEdgeSpan = 1;  // mm, the least w
constexpr double kSlopeSpan = 3;    // mm
constexpr double kMinStep = 2;      // mm: a bare profile steps less, its noise and the nasal dorsum included
constexpr double kMaxHeight = 80;   // mm: a strap or a band of tape is narrower
constexpr double kMaxStepRatio = 2;
constexpr double kSkinMargin = 5;  // mm below and above the object over which the skin under it is given
constexpr double kSkinStep = 0.5;  // mm between its points

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Edge {
  double z, thickness;
};

}  // namespace

std::vector<SkinObject> find_skin_objects(const Field& ct, double skin_threshold, const MidSagittalPlane& plane,
                                          const Eigen::Vector3d& pronasale) {
  const HeadTurn frame = head_turn_of(plane);
  const MidSagittalPlane head_plane = frame.to_head(plane);
  const Eigen::Vector3d tip = frame.to_head(pronasale);
  const double z0 = tip.z() + kAbovePronasale, z1 = tip.z() + kReach;
  const auto centre = [&](double z) { return head_plane.x_at(tip.y(), z); };
  const double margin = FaceFront::kGrid;
  const double x0 = std::min(centre(z0), centre(z1)) - kProfileHalfWidth - margin;
  const double x1 = std::max(centre(z0), centre(z1)) + kProfileHalfWidth + margin;
  const FaceFront front(ct, skin_threshold, frame, x0, x1, z0, z1, tip.y() + kRayFront, tip.y() - kRayBack);

  std::vector<double> profile;
  for (double z = z0; z <= z1 + 1e-9; z += kStep) profile.push_back(front.mean_across(centre(z), kProfileHalfWidth, z));
  const int n = static_cast<int>(profile.size());
  const double w = std::max(kMinEdgeSpan, std::abs(ct.geometry.spacing.z()));
  const int wi = static_cast<int>(std::lround(w / kStep)), si = static_cast<int>(std::lround(kSlopeSpan / kStep));
  // The median slope over [from, from + si] samples: the slope of the skin there, whatever step or voxel stair a few
  // of its samples hold.
  const auto slope = [&](int from) {
    std::vector<double> d;
    for (int i = from; i < from + si; ++i) d.push_back(profile[i + 1] - profile[i]);
    std::nth_element(d.begin(), d.begin() + si / 2, d.end());
    return d[si / 2] / kStep;
  };
  std::vector<double> step(static_cast<size_t>(n), kNaN);
  for (int i = wi + si; i + wi + si < n; ++i)
    step[i] = profile[i + wi] - profile[i - wi] - w * (slope(i - wi - si) + slope(i + wi));
  // Rule 1's edges: the largest step of either sign within w either side.
  std::vector<Edge> lower, upper;
  for (int i = 0; i < n; ++i) {
    if (!(std::abs(step[i]) >= kMinStep)) continue;
    const double sign = step[i] > 0 ? 1 : -1;
    bool largest = true;
    for (int j = std::max(0, i - wi); j <= std::min(n - 1, i + wi) && largest; ++j)  // the first of equals
      if (j < i ? sign * step[j] >= sign * step[i] : sign * step[j] > sign * step[i]) largest = false;
    if (!largest) continue;
    // Rule 2: the step over the skin outside the object continued with its own slope.
    const double outside = sign > 0 ? slope(i - wi - si) : slope(i + wi);
    // The edge where the profile changes fastest within w: the middle of the grey values' blend across it.
    int steepest = i;
    for (int j = std::max(0, i - wi); j < std::min(n - 1, i + wi); ++j)
      if (sign * (profile[j + 1] - profile[j]) > sign * (profile[steepest + 1] - profile[steepest])) steepest = j;
    (sign > 0 ? lower : upper)
        .push_back({z0 + (steepest + 0.5) * kStep, sign * (profile[i + wi] - profile[i - wi] - 2 * w * outside)});
  }
  // The profile at z, linear between its points.
  const auto at = [&](double z) {
    const double g = std::clamp((z - z0) / kStep, 0.0, n - 1.0);
    const int i = std::min(static_cast<int>(g), n - 2);
    return profile[i] + (profile[i + 1] - profile[i]) * (g - i);
  };
  std::vector<SkinObject> objects;
  for (size_t a = 0; a < lower.size(); ++a) {
    const auto b = std::find_if(upper.begin(), upper.end(), [&](const Edge& e) { return e.z > lower[a].z; });
    if (b == upper.end()) break;
    if (a + 1 < lower.size() && lower[a + 1].z < b->z) continue;
    const double ratio = std::max(lower[a].thickness, b->thickness) / std::min(lower[a].thickness, b->thickness);
    if (b->z - lower[a].z > kMaxHeight || !(std::min(lower[a].thickness, b->thickness) > 0) || ratio > kMaxStepRatio)
      continue;
    SkinObject o{lower[a].z, b->z, lower[a].thickness, b->thickness, {}};
    // Rule 3.
    const auto line = [](double z, double za, double ya, double zb, double yb) {
      return ya + (yb - ya) * (z - za) / (zb - za);
    };
    const auto thickness = [&](double z) { return line(z, o.z_low, o.thickness_low, o.z_high, o.thickness_high); };
    const double below = o.z_low - w, above = o.z_high + w, lo = o.z_low + w, hi = o.z_high - w;
    const auto skin = [&](double z) {
      if (z <= below || z >= above) return at(z);
      if (lo >= hi) return line(z, below, at(below), above, at(above));  // too short for a middle
      if (z < lo) return line(z, below, at(below), lo, at(lo) - thickness(lo));
      if (z > hi) return line(z, hi, at(hi) - thickness(hi), above, at(above));
      return at(z) - thickness(z);
    };
    for (double z = o.z_low - kSkinMargin; z <= o.z_high + kSkinMargin + 1e-9; z += kSkinStep)
      if (z >= z0 && z <= z1 && std::isfinite(skin(z))) o.skin.emplace_back(z, skin(z));
    if (o.skin.size() >= 2) objects.push_back(std::move(o));
  }
  return objects;
}

}  // namespace facehex
