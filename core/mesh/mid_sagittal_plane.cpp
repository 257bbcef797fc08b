#include "core/mesh/mid_sagittal_plane.h"

#include <cmath>

#include "core/util/error.h"

namespace facehex {

std::optional<MidSagittalPlane> mid_sagittal_plane(const VolumeMesh& mesh, const std::string& source) {
  const auto field = mesh.field_data.find(kMidSagittalPlaneField);
  if (field == mesh.field_data.end()) return std::nullopt;
  const Eigen::MatrixXd& p = field->second;
  if (p.size() != 3 || !p.allFinite() || std::abs(p(0, 1)) > 1.0)
    throw Error(source, std::string("the field data '") + kMidSagittalPlaneField +
                            "' (the mid-sagittal plane: x, slope dx/dz within 1, z) is not three finite numbers; "
                            "remove it to have the plane found from the skin");
  return MidSagittalPlane{p(0, 0), p(0, 1), p(0, 2)};
}

void set_mid_sagittal_plane(VolumeMesh& mesh, const MidSagittalPlane& plane) {
  mesh.field_data[kMidSagittalPlaneField] = (Eigen::MatrixXd(1, 3) << plane.x, plane.slope, plane.z).finished();
}

}  // namespace facehex
