#pragma once
// The mid-sagittal plane a model carries as field data "mid_sagittal_plane" (1 x 3: x, slope, z; mm, the model's
// frame): x_at(z') = x + slope (z' - z), a vertical plane leaning towards a shoulder by atan(slope). A segmented CT's
// is the plane its cuts were placed by, found from the whole head's mirror symmetry (core/segment/face_anatomy.h). The
// landmark finder takes it (core/face/face_landmarks.h) rather than reading the plane again from the face's skin
// alone, so that `facehex run CT` and `facehex segment` + `facehex run MODEL` find the same landmarks.
#include <optional>
#include <string>

#include "core/mesh/mesh.h"

namespace facehex {

inline constexpr char kMidSagittalPlaneField[] = "mid_sagittal_plane";

struct MidSagittalPlane {
  double x = 0, slope = 0, z = 0;
  double x_at(double at_z) const { return x + slope * (at_z - z); }
};

// The plane, or none when the model does not carry one. Throws facehex::Error(source, ...) when the field data is not
// three finite numbers with a slope within 45 degrees of vertical.
std::optional<MidSagittalPlane> mid_sagittal_plane(const VolumeMesh& mesh, const std::string& source);

void set_mid_sagittal_plane(VolumeMesh& mesh, const MidSagittalPlane& plane);

}  // namespace facehex
