#pragma once
// The CT's skin a segmented model carries as field data "skin_points" (#P x 3, mm, the model's frame): the skin
// side's vertices of the segmentation's iso-surface before it is remeshed to the model's edge length, so at the
// segmentation's working spacing (core/segment/soft_tissue.h), of its first surface when a tunnel repair made it again
// (the repair's wider blur flattens the lips' edges). The remeshed skin bridges grooves these points keep
// (closed lips, the ends of the mouth line), and the landmark finder reads the face from them when a model carries
// them (core/face/face_landmarks.h), so that `facehex run CT` and `facehex segment` + `facehex run MODEL` find the
// same landmarks.
#include <optional>
#include <string>

#include "core/mesh/mesh.h"

namespace facehex {

inline constexpr char kSkinPointsField[] = "skin_points";

// The points, or none when the model does not carry them. Throws facehex::Error(source, ...) when the field data is
// not a non-empty #P x 3 array of finite numbers.
std::optional<Eigen::MatrixXd> skin_points(const VolumeMesh& mesh, const std::string& source);

void set_skin_points(VolumeMesh& mesh, const Eigen::MatrixXd& points);

}  // namespace facehex
