#pragma once
// Landmarks the segmentation reads in the CT itself, which a segmented model carries as field data "ct_landmarks"
// (7 x 4, mm, the model's frame): one row per name of kCtLandmarkNames, each x, y, z and 1 where it is estimated (0:
// found); a row of NaN: not seen. They lie where the model's skin does not show them: the tragi
// (core/segment/tragus.h) behind the model's posterior cut, the eye corners (core/segment/eye_corners.h) and the
// stomion (core/segment/stomion.h) in the closed eyes' and lips' slits, which the model's smoothed skin bridges. The
// landmark finder takes them from the model (core/face/face_landmarks.h), the stomion in place of its own.
#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>

#include "core/mesh/mesh.h"

namespace facehex {

inline constexpr char kCtLandmarksField[] = "ct_landmarks";

struct CtLandmark {
  Eigen::Vector3d point;
  bool estimated = false;
};

// Right (-x) and left (+x).
using Tragi = std::array<std::optional<CtLandmark>, 2>;
inline constexpr std::array<const char*, 2> kTragusNames = {"tragus right", "tragus left"};
// Endocanthion right, exocanthion right, endocanthion left, exocanthion left.
using EyeCorners = std::array<std::optional<CtLandmark>, 4>;
inline constexpr std::array<const char*, 4> kEyeCornerNames = {"endocanthion right", "exocanthion right",
                                                               "endocanthion left", "exocanthion left"};

inline constexpr char kStomionName[] = "stomion";

struct CtLandmarks {
  Tragi tragi;
  EyeCorners eye_corners;
  std::optional<CtLandmark> stomion;
};

// The field data's rows: the tragi, the eye corners, the stomion.
inline constexpr std::array<const char*, 7> kCtLandmarkNames = {
    kTragusNames[0],    kTragusNames[1],    kEyeCornerNames[0], kEyeCornerNames[1],
    kEyeCornerNames[2], kEyeCornerNames[3], kStomionName};

// The landmarks, or none when the model does not carry them. Throws facehex::Error(source, ...) when the field data is
// not 7 x 4 with rows of finite numbers (or all NaN) and a status of 0 or 1.
std::optional<CtLandmarks> ct_landmarks(const VolumeMesh& mesh, const std::string& source);

void set_ct_landmarks(VolumeMesh& mesh, const CtLandmarks& landmarks);

}  // namespace facehex
