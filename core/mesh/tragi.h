#pragma once
// The tragi a segmented model carries as field data "tragi" (2 x 4, mm, the model's frame): row 0 the right tragus
// (towards -x), row 1 the left, each x, y, z and 1 where it is estimated (0: found). A row of NaN: that side's tragus
// was not seen. The segmentation finds them in the CT (core/segment/face_anatomy.h, rule 6): they lie behind the
// model's posterior cut, on no skin the landmark finder reads, so the model keeps them for it
// (core/face/face_landmarks.h).
#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>

#include "core/mesh/mesh.h"

namespace facehex {

inline constexpr char kTragiField[] = "tragi";

struct Tragus {
  Eigen::Vector3d point;
  bool estimated = false;
};

// Right (-x) and left (+x).
using Tragi = std::array<std::optional<Tragus>, 2>;
// The landmark names of Tragi's two sides (core/face/landmark_file.h).
inline constexpr std::array<const char*, 2> kTragusNames = {"tragus right", "tragus left"};

// The tragi, or none when the model does not carry them. Throws facehex::Error(source, ...) when the field data is
// not 2 x 4 with rows of finite numbers (or all NaN) and a status of 0 or 1.
std::optional<Tragi> tragi(const VolumeMesh& mesh, const std::string& source);

void set_tragi(VolumeMesh& mesh, const Tragi& tragi);

}  // namespace facehex
