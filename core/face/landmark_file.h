#pragma once
// Named landmark points in files, for the user to give or check the landmarks the constraints are placed at.
//
// Two formats, told apart by the name (".mrk.json": 3D Slicer markups; any other ".json": FaceHex's own):
//  - FaceHex: {"format": "facehex-landmarks", "version": 1, "units": "mm",
//              "landmarks": [{"name": "pronasale", "position": [x, y, z], "status": "found"}, ...]}
//    in the segmentation frame (+y anterior, +z superior, +x lateral: the side whose landmarks are named left, see
//    below); "status" is "found", "estimated" (placed by proportions, e.g. inside a field-of-view cut) or "given" (by
//    the user), and may be left out (then "given").
//  - 3D Slicer markups (schema markups-schema-v1.0.3): {"markups": [{"type": "Fiducial", "coordinateSystem": "LPS"
//    or "RAS", "coordinateUnits": "mm", "controlPoints": [{"label": "pronasale", "position": [x, y, z]}, ...]}]}.
//    The segmentation frame of a CT read without reorientation is the file's physical frame, which Slicer takes as
//    LPS: points are written as LPS and read from LPS unchanged or from RAS with x and y negated. A control point's
//    "description" carries the status.
// Left and right: a paired landmark at +x of the segmentation frame is named left. That is the patient's left on a
// volume whose stored frame is a mirror image of the patient (as the two CTs of tests/data/landmarks are taken to
// be), but the patient's right on a DICOM series, which the reader turns half a turn about the vertical axis into
// the right-handed segmentation frame (core/segment/ct_volume.h); and the Slicer file of such a model is in the
// segmentation frame, not the series' LPS. A known limitation: docs/user-guide.md section 3.
// Names are those of kLandmarkNames; unknown names, duplicates, missing or non-finite coordinates, other units or
// coordinate systems are errors naming the file and the point.
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

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

// Throws facehex::Error(path, problem).
std::vector<NamedLandmark> read_landmark_file(const std::string& path);
// Writes atomically; the format follows the name as above.
void write_landmark_file(const std::string& path, const std::vector<NamedLandmark>& landmarks);

}  // namespace facehex
