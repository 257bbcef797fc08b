#pragma once
// Named landmark points in files, for the user to give or check the landmarks the constraints are placed at.
//
// Two formats, told apart by the name (".mrk.json": 3D Slicer markups; any other ".json": FaceHex's own):
//  - FaceHex: {"format": "facehex-landmarks", "version": 1, "units": "mm",
//              "landmarks": [{"name": "pronasale", "position": [x, y, z], "status": "found"}, ...]}
//    in the model's frame (the segmentation frame: +y anterior, +z superior, see core/segment/ct_volume.h); "status" is
//    "found", "estimated" (placed by proportions, e.g. inside a field-of-view cut) or "given" (by the user), and may
//    be left out (then "given").
//  - 3D Slicer markups (schema markups-schema-v1.0.3): {"markups": [{"type": "Fiducial", "coordinateSystem": "LPS"
//    or "RAS", "coordinateUnits": "mm", "controlPoints": [{"label": "pronasale", "position": [x, y, z]}, ...]}]}
//    in the scan's patient frame, where Slicer shows the CT the model was segmented from: written as LPS; read from
//    LPS, or from RAS with x and y negated; and taken to the model's frame by its scan frame (core/mesh/scan_frame.h).
//    A control point's "description" carries the status.
// Left and right in both formats are the patient's by the scan frame: the landmarks a model names by its sides (its
// +x one left) are renamed on writing and reading where the patient's left lies at the model's -x (a DICOM series,
// which its reader turns half a turn about the vertical axis into the right-handed segmentation frame). A model
// without a scan frame (a mesh made elsewhere) names them by its sides.
// Names are those of kLandmarkNames; unknown names, duplicates, missing or non-finite coordinates, other units or
// coordinate systems are errors naming the file and the point.
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

#include "core/mesh/scan_frame.h"

namespace facehex {

enum class LandmarkStatus { found, estimated, given };

struct NamedLandmark {
  std::string name;
  Eigen::Vector3d position;
  LandmarkStatus status = LandmarkStatus::given;
};

// The standard facial landmarks FaceHex knows, in anatomical order: the mid-sagittal profile from the top, then the
// paired ones (left, then right: +x, then -x).
const std::vector<std::string>& landmark_names();
// Whether `name` is one of landmark_names(); and those names joined by ", ", for messages.
bool is_landmark_name(const std::string& name);
std::string landmark_names_text();
// Whether the landmark lies on a face model's skin: all but the tragi, which lie behind its posterior cut (the
// segmentation finds them in the CT, core/mesh/ct_landmarks.h).
bool lies_on_model_skin(const std::string& name);

const char* status_name(LandmarkStatus status);

// The landmarks of a file placed on the model whose scan frame is `frame`, as the model names them, in its frame.
// Throws facehex::Error(path, problem).
std::vector<NamedLandmark> read_landmark_file(const std::string& path, const ScanFrame& frame = {});
// Writes a model's landmarks (as it names them, in its frame) atomically; the format follows the name as above.
void write_landmark_file(const std::string& path, const std::vector<NamedLandmark>& landmarks,
                         const ScanFrame& frame = {});

}  // namespace facehex
