#pragma once
// Landmarks the segmentation reads in the CT itself, which a segmented model carries as field data "ct_landmarks"
// (10 x 4, mm, the model's frame): one row per name of kCtLandmarkNames, each x, y, z and 1 where it is estimated (0:
// found); a row of NaN: not seen. A table of the first 7 or more rows only (a model written before the later rows)
// is read with the rows it lacks not seen. They lie where the model's skin does not show them: the tragi
// (core/segment/tragus.h) behind the model's posterior cut, the eye corners (core/segment/eye_corners.h), the stomion
// (core/segment/stomion.h) and the mouth corners (core/segment/mouth_slit.h) in the closed eyes' and lips' slits, which
// the model's smoothed skin bridges. The landmark finder takes them from the model (core/face/face_landmarks.h), the
// stomion and the mouth corners in place of its own, and reads the soft-tissue menton under the bony one.
// With them, as field data "skin_objects" (#O x 4: z_low, z_high, the two thicknesses) and "skin_under_objects" (#S x
// 3: the object's row, z, y), the objects the segmentation found lying on the face's front (a strap, thick tape:
// core/segment/skin_objects.h), which the model's skin includes and the landmark finder reads the profile under.
#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/mesh/mesh.h"

namespace facehex {

inline constexpr char kCtLandmarksField[] = "ct_landmarks";
inline constexpr char kSkinObjectsField[] = "skin_objects";
inline constexpr char kSkinUnderObjectsField[] = "skin_under_objects";

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
// Right (-x) and left (+x).
using MouthCorners = std::array<std::optional<CtLandmark>, 2>;
inline constexpr std::array<const char*, 2> kMouthCornerNames = {"cheilion right", "cheilion left"};
// The lowest point of the chin's bone near the mid-sagittal plane (core/segment/face_anatomy.h), under which the
// landmark finder reads the soft-tissue menton.
inline constexpr char kBonyMentonName[] = "bony menton";

// An object lying on the face's front over the heights z_low to z_high (mm, the head frame of the model's mid-sagittal
// plane, core/mesh/head_turn.h, in which the landmark finder reads the profile), as thick as its edges' steps, and the
// skin's profile under it as the CT shows it: (z, y) on the plane, bottom up, from below its lower edge to above its
// upper one.
struct SkinObject {
  double z_low = 0, z_high = 0;
  double thickness_low = 0, thickness_high = 0;  // mm
  std::vector<Eigen::Vector2d> skin;
};

struct CtLandmarks {
  Tragi tragi;
  EyeCorners eye_corners;
  std::optional<CtLandmark> stomion;
  MouthCorners mouth_corners;
  std::optional<CtLandmark> bony_menton;
  std::vector<SkinObject> skin_objects;  // bottom up
};

// The field data's rows: the tragi, the eye corners, the stomion, the mouth corners, the bony menton.
inline constexpr std::array<const char*, 10> kCtLandmarkNames = {
    kTragusNames[0],    kTragusNames[1], kEyeCornerNames[0],   kEyeCornerNames[1],   kEyeCornerNames[2],
    kEyeCornerNames[3], kStomionName,    kMouthCornerNames[0], kMouthCornerNames[1], kBonyMentonName};

// The landmarks, or none when the model does not carry them. Throws facehex::Error(source, ...) when the field data is
// not 7 to 10 rows x 4 with rows of finite numbers (or all NaN) and a status of 0 or 1, or the skin objects' are not #O
// x 4 rows of finite numbers with z_low < z_high and positive thicknesses and, for each, at least two rows of the skin
// under it with z increasing.
std::optional<CtLandmarks> ct_landmarks(const VolumeMesh& mesh, const std::string& source);

void set_ct_landmarks(VolumeMesh& mesh, const CtLandmarks& landmarks);

}  // namespace facehex
