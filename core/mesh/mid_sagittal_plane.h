#pragma once
// The mid-sagittal plane x = const a model carries as field data "mid_sagittal_x" (1 x 1, mm, the model's frame): a
// segmented CT's, found from the whole head's mirror symmetry (core/segment/face_anatomy.h). The landmark finder
// takes it (core/face/face_landmarks.h) rather than reading the plane again from the face's skin alone, so that
// `facehex run CT` and `facehex segment` + `facehex run MODEL` find the same landmarks.
#include <optional>
#include <string>

#include "core/mesh/mesh.h"

namespace facehex {

inline constexpr char kMidSagittalXField[] = "mid_sagittal_x";

// The plane's x, or none when the model does not carry one. Throws facehex::Error(source, ...) when the field data is
// not a single finite number.
std::optional<double> mid_sagittal_x(const VolumeMesh& mesh, const std::string& source);

void set_mid_sagittal_x(VolumeMesh& mesh, double x);

}  // namespace facehex
