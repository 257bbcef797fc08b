#include "core/mesh/mid_sagittal_plane.h"

#include <cmath>

#include "core/util/error.h"

namespace facehex {

std::optional<double> mid_sagittal_x(const VolumeMesh& mesh, const std::string& source) {
  const auto field = mesh.field_data.find(kMidSagittalXField);
  if (field == mesh.field_data.end()) return std::nullopt;
  const Eigen::MatrixXd& x = field->second;
  if (x.size() != 1 || !std::isfinite(x(0, 0)))
    throw Error(source, std::string("the field data '") + kMidSagittalXField +
                            "' (the mid-sagittal plane's x) is not one finite number; remove it to have the plane "
                            "found from the skin");
  return x(0, 0);
}

void set_mid_sagittal_x(VolumeMesh& mesh, double x) {
  mesh.field_data[kMidSagittalXField] = Eigen::MatrixXd::Constant(1, 1, x);
}

}  // namespace facehex
