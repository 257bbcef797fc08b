#pragma once
// Where a model lies in the scan it was segmented from, and which of its sides is the patient's left.
//
// FaceHex works in the segmentation frame (core/segment/ct_volume.h: +y anterior, +z superior, right-handed), which a
// CT's reader reaches from the file's own frame by a signed permutation of its axes. The scan frame is the file's
// patient frame as ITK and 3D Slicer read it, in LPS (+x the patient's left, +y posterior, +z superior): a DICOM
// series' patient coordinates, a NIfTI file's world coordinates with x and y negated, the physical coordinates of a
// MetaImage, NRRD (LPS unless its "space" says RAS) or VTK image file. A segmented model carries the map as field
// data "scan_frame" (3 x 4: [R | t], p_scan = R p_model + t, R orthogonal), so that landmark files placed on the scan
// in another tool are read where they belong and the landmarks FaceHex writes open there (core/face/landmark_file.h).
// A model without it (a mesh made elsewhere, the standard) is taken to be in its own scan frame: R = I, t = 0.
//
// Paired landmarks are found and transferred by the side of the model they lie on (core/face/face_landmarks.h names
// the +x one left, in the standard and in the patient alike, so that the transfer pairs them without a mirror);
// patient_side_name turns such a name into the patient's side by the scan frame, for every file and text a user
// reads or writes.
#include <optional>
#include <string>

#include "core/mesh/mesh.h"

namespace facehex {

inline constexpr char kScanFrameField[] = "scan_frame";

struct ScanFrame {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // R: model axes -> scan axes (orthogonal)
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();   // t, mm

  Eigen::Vector3d to_scan(const Eigen::Vector3d& model) const { return rotation * model + translation; }
  Eigen::Vector3d from_scan(const Eigen::Vector3d& scan) const { return rotation.transpose() * (scan - translation); }
  // Whether the patient's left (the scan's +x) lies towards the model's -x: then the landmarks the model names left
  // (its +x side) are the patient's right.
  bool left_at_minus_x() const { return rotation(0, 0) < 0; }
  // This frame after the model's coordinates are changed by p_new = A p_old + b (A orthogonal).
  ScanFrame after_model_change(const Eigen::Matrix3d& A, const Eigen::Vector3d& b) const;
};

// The frame the model carries, or the identity when it carries none. Throws facehex::Error(source, ...) when the field
// data is not 3 x 4 finite numbers whose first three columns are orthogonal (within 1e-6).
ScanFrame scan_frame(const VolumeMesh& mesh, const std::string& source);

// Stores the frame; the identity is stored too (a model from a CT always says where it lies).
void set_scan_frame(VolumeMesh& mesh, const ScanFrame& frame);

// "the patient's left at -x of the model; model (x, y, z) at scan (-x + 250.0, -y + 250.0, z - 40.0) mm (LPS)" for a
// frame whose rotation permutes and flips the axes; the rotation's rows and the offset otherwise.
std::string scan_frame_text(const ScanFrame& frame);

// Which side a landmark's name says: +1 for a paired one named left (the model's +x side), -1 for one named right, 0
// for one on the midline.
int named_side(const std::string& name);
// The same landmark on the other side ("cheilion left" <-> "cheilion right"); a midline name unchanged.
std::string other_side_name(const std::string& name);

// A landmark's name as the model names it (its +x side left) turned into the patient's side by `frame`: "left" and
// "right" swapped at the end of a paired landmark's name when the patient's left lies at -x, unchanged otherwise. Its
// own inverse: a name read from a user's file is turned into the model's name by the same call.
std::string patient_side_name(const std::string& name, const ScanFrame& frame);

}  // namespace facehex
