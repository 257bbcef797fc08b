#include "core/mesh/mid_sagittal_plane.h"

#include <cmath>
#include <sstream>

#include "core/util/error.h"

namespace facehex {

std::optional<MidSagittalPlane> mid_sagittal_plane(const VolumeMesh& mesh, const std::string& source) {
  const auto field = mesh.field_data.find(kMidSagittalPlaneField);
  if (field == mesh.field_data.end()) return std::nullopt;
  const Eigen::MatrixXd& p = field->second;
  if ((p.size() != 3 && p.size() != 5 && p.size() != 6) || !p.allFinite() || std::abs(p(0, 1)) > 1.0 ||
      (p.size() >= 5 && std::abs(p(0, 3)) > 1.0) || (p.size() == 6 && std::abs(p(0, 5)) > 45.0))
    throw Error(source, std::string("the field data '") + kMidSagittalPlaneField +
                            "' (the mid-sagittal plane: x, slope dx/dz within 1, z, and turn dx/dy within 1, y, and "
                            "pitch within 45 degrees) is not three, five or six finite numbers; remove it to have the "
                            "plane found from the skin");
  MidSagittalPlane plane{p(0, 0), p(0, 1), p(0, 2)};
  if (p.size() >= 5) plane.turn = p(0, 3), plane.y = p(0, 4);
  if (p.size() == 6) plane.pitch = p(0, 5);
  return plane;
}

void set_mid_sagittal_plane(VolumeMesh& mesh, const MidSagittalPlane& plane) {
  mesh.field_data[kMidSagittalPlaneField] =
      plane.pitch != 0
          ? (Eigen::MatrixXd(1, 6) << plane.x, plane.slope, plane.z, plane.turn, plane.y, plane.pitch).finished()
      : plane.turn == 0 ? (Eigen::MatrixXd(1, 3) << plane.x, plane.slope, plane.z).finished()
                        : (Eigen::MatrixXd(1, 5) << plane.x, plane.slope, plane.z, plane.turn, plane.y).finished();
}

std::string mid_sagittal_plane_text(const MidSagittalPlane& plane) {
  constexpr double kDegrees = 180 / M_PI;
  std::ostringstream s;
  s.precision(1);
  s << std::fixed << "x = " << plane.x << " mm at ";
  if (plane.turn != 0 || plane.pitch != 0) s << "y = " << plane.y << " mm, ";
  s << "z = " << plane.z << " mm, leaning " << std::atan(plane.slope) * kDegrees << " degrees";
  if (plane.turn != 0) s << ", turned " << std::atan(plane.turn) * kDegrees << " degrees";
  if (plane.pitch != 0) s << ", pitched " << plane.pitch << " degrees";
  return s.str();
}

}  // namespace facehex
