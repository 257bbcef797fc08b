#include "core/segment/stomion.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/mesh/head_turn.h"
#include "core/segment/face_front.h"

namespace facehex {
namespace {

constexpr double kProfileHalfWidth = 2;  // mm either side of the plane: a column's noise averaged, the lips' shape not
constexpr double kStep = 0.25;           // mm between the profile's points
constexpr double kRayFront = 10;         // mm in front of the more anterior lip where the rays start
constexpr double kRayBack = 40;          // mm behind the less anterior one where they give up
// mm: closed lips' slit is a few millimetres deep behind the lips' fronts; teeth behind parted lips lie deeper.
constexpr double kMaxSlitDepth = 8;

// The profile between the lips, in the head frame: points every kStep from the labrale inferius up to the labrale
// superius, y NaN where the rays meet no skin; `back_y` the less anterior lip's y. Empty where the labralia are not one
// above the other.
struct LipsProfile {
  HeadTurn frame;
  std::vector<Eigen::Vector3d> points;
  double back_y = 0;
};

LipsProfile lips_profile(const Field& ct, double skin_threshold, const MidSagittalPlane& plane,
                         const Eigen::Vector3d& labrale_superius, const Eigen::Vector3d& labrale_inferius) {
  LipsProfile profile{head_turn_of(plane), {}, 0};
  const Eigen::Vector3d top = profile.frame.to_head(labrale_superius), bottom = profile.frame.to_head(labrale_inferius);
  if (!(top.z() > bottom.z())) return profile;
  const double centre = profile.frame.to_head(plane).x_at(top.y(), 0.5 * (top.z() + bottom.z()));
  const double front_y = std::max(top.y(), bottom.y());
  profile.back_y = std::min(top.y(), bottom.y());
  // A grid point beyond each end, so that the profile's every point lies inside it.
  const double margin = FaceFront::kGrid;
  const FaceFront front(ct, skin_threshold, profile.frame, centre - kProfileHalfWidth - margin,
                        centre + kProfileHalfWidth + margin, bottom.z() - margin, top.z() + margin, front_y + kRayFront,
                        profile.back_y - kRayBack);
  for (double z = bottom.z(); z <= top.z() + 1e-9; z += kStep)
    profile.points.emplace_back(centre, front.mean_across(centre, kProfileHalfWidth, z), z);
  return profile;
}

}  // namespace

std::optional<CtLandmark> find_stomion(const Field& ct, double skin_threshold, const MidSagittalPlane& plane,
                                       const Eigen::Vector3d& labrale_superius,
                                       const Eigen::Vector3d& labrale_inferius) {
  const LipsProfile lips = lips_profile(ct, skin_threshold, plane, labrale_superius, labrale_inferius);
  const std::vector<Eigen::Vector3d>& profile = lips.points;
  if (std::any_of(profile.begin(), profile.end(), [](const Eigen::Vector3d& p) { return std::isnan(p.y()); }))
    return std::nullopt;
  const auto rearmost = std::min_element(
      profile.begin(), profile.end(), [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a.y() < b.y(); });
  // At either end of the profile there is no slit between the lips.
  if (profile.size() < 3 || rearmost == profile.begin() || rearmost == profile.end() - 1 ||
      rearmost->y() < lips.back_y - kMaxSlitDepth)
    return std::nullopt;
  return CtLandmark{lips.frame.to_model(*rearmost), false};
}

double parted_lips_gap(const Field& ct, double skin_threshold, const MidSagittalPlane& plane,
                       const Eigen::Vector3d& labrale_superius, const Eigen::Vector3d& labrale_inferius) {
  const LipsProfile lips = lips_profile(ct, skin_threshold, plane, labrale_superius, labrale_inferius);
  double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
  for (const Eigen::Vector3d& p : lips.points)
    if (std::isnan(p.y()) || p.y() < lips.back_y - kMaxSlitDepth)
      lowest = std::min(lowest, p.z()), highest = std::max(highest, p.z());
  return highest >= lowest ? highest - lowest + kStep : 0;
}

}  // namespace facehex
