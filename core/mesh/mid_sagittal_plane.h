#pragma once
// The mid-sagittal plane a model carries as field data "mid_sagittal_plane" (1 x 6: x, slope, z, turn, y, pitch; mm,
// the model's frame; 1 x 5 when pitch is 0, 1 x 3 when turn is 0 too): x_at(y', z') = x + slope (z' - z) + turn (y' -
// y), a plane leaning towards a shoulder by atan(slope) and turned about the vertical axis by atan(turn) (the face
// looks towards (turn, 1, 0)); pitch, degrees, is how far the head is pitched (the chin raised) within the plane
// (core/mesh/head_turn.h), which the plane alone does not show. A
// segmented CT's is the plane its cuts were placed by, found from the whole head's mirror symmetry
// (core/segment/face_anatomy.h). The landmark finder takes it (core/face/face_landmarks.h) rather than reading the
// plane again from the face's skin alone, so that `facehex run CT` and `facehex segment` + `facehex run MODEL` find
// the same landmarks.
#include <optional>
#include <string>

#include "core/mesh/mesh.h"

namespace facehex {

inline constexpr char kMidSagittalPlaneField[] = "mid_sagittal_plane";

struct MidSagittalPlane {
  double x = 0, slope = 0, z = 0;
  double turn = 0, y = 0;
  double pitch = 0;
  double x_at(double at_y, double at_z) const { return x + slope * (at_z - z) + turn * (at_y - y); }
  Eigen::Vector3d normal() const { return Eigen::Vector3d(1, -turn, -slope).normalized(); }
};

// The plane, or none when the model does not carry one. Throws facehex::Error(source, ...) when the field data is not
// three, five or six finite numbers with a slope, a turn and a pitch within 45 degrees.
std::optional<MidSagittalPlane> mid_sagittal_plane(const VolumeMesh& mesh, const std::string& source);

void set_mid_sagittal_plane(VolumeMesh& mesh, const MidSagittalPlane& plane);

// "x = 98.4 mm at z = 80.0 mm, leaning 1.2 degrees" and, when turned, "at y = 60.0 mm, ..., turned -10.0 degrees";
// when pitched, "..., pitched 12.0 degrees".
std::string mid_sagittal_plane_text(const MidSagittalPlane& plane);

}  // namespace facehex
