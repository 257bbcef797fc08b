#include "core/mesh/skin_points.h"

#include "core/util/error.h"

namespace facehex {

std::optional<Eigen::MatrixXd> skin_points(const VolumeMesh& mesh, const std::string& source) {
  const auto field = mesh.field_data.find(kSkinPointsField);
  if (field == mesh.field_data.end()) return std::nullopt;
  const Eigen::MatrixXd& p = field->second;
  if (p.rows() == 0 || p.cols() != 3 || !p.allFinite())
    throw Error(source, std::string("the field data '") + kSkinPointsField + "' (the CT's skin points, #P x 3 mm) is " +
                            std::to_string(p.rows()) + " x " + std::to_string(p.cols()) +
                            (p.allFinite() ? "" : " with numbers that are not finite") +
                            "; remove it to have the landmarks found on the model's own skin");
  return p;
}

void set_skin_points(VolumeMesh& mesh, const Eigen::MatrixXd& points) { mesh.field_data[kSkinPointsField] = points; }

}  // namespace facehex
