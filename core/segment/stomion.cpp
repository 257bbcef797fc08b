#include "core/segment/stomion.h"

#include <algorithm>
#include <cmath>
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

}  // namespace

std::optional<CtLandmark> find_stomion(const Field& ct, double skin_threshold, const MidSagittalPlane& plane,
                                       const Eigen::Vector3d& labrale_superius,
                                       const Eigen::Vector3d& labrale_inferius) {
  const HeadTurn frame = head_turn_of(plane);
  const Eigen::Vector3d top = frame.to_head(labrale_superius), bottom = frame.to_head(labrale_inferius);
  if (!(top.z() > bottom.z())) return std::nullopt;
  const double centre = frame.to_head(plane).x_at(top.y(), 0.5 * (top.z() + bottom.z()));
  const double front_y = std::max(top.y(), bottom.y()), back_y = std::min(top.y(), bottom.y());
  // A grid point beyond each end, so that the profile's every point lies inside it.
  const double margin = FaceFront::kGrid;
  const FaceFront front(ct, skin_threshold, frame, centre - kProfileHalfWidth - margin,
                        centre + kProfileHalfWidth + margin, bottom.z() - margin, top.z() + margin, front_y + kRayFront,
                        back_y - kRayBack);
  std::vector<Eigen::Vector3d> profile;
  for (double z = bottom.z(); z <= top.z() + 1e-9; z += kStep) {
    const double y = front.mean_across(centre, kProfileHalfWidth, z);
    if (std::isnan(y)) return std::nullopt;
    profile.emplace_back(centre, y, z);
  }
  const auto rearmost = std::min_element(
      profile.begin(), profile.end(), [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a.y() < b.y(); });
  // At either end of the profile there is no slit between the lips.
  if (profile.size() < 3 || rearmost == profile.begin() || rearmost == profile.end() - 1 ||
      rearmost->y() < back_y - kMaxSlitDepth)
    return std::nullopt;
  return CtLandmark{frame.to_model(*rearmost), false};
}

}  // namespace facehex
