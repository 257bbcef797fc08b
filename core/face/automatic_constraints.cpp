#include "core/face/automatic_constraints.h"

#include <iomanip>
#include <sstream>
#include <utility>

#include "core/mesh/side_mask.h"
#include "core/util/error.h"

namespace facehex {
namespace {

// A given landmark this far from the model's skin was placed on another scan or read in another frame; the skin
// bridges a closed eye's or mouth's slit a few millimetres in front of the corners placed in it.
constexpr double kGivenOffSkin = 10.0;  // mm

void check_on_skin(const FaceLandmarks& given, const Eigen::MatrixXd& V, const Eigen::VectorXi& side_mask) {
  for (const auto& [name, x] : given.points) {
    if (!lies_on_model_skin(name)) continue;
    const int nearest = closest_skin_vertex(V, side_mask, x);
    if (nearest < 0) return;  // no skin: the features fail on their own
    const double off = (V.row(nearest).transpose() - x).norm();
    if (off > kGivenOffSkin) {
      std::ostringstream text;
      text << std::fixed << std::setprecision(1) << "the given " << patient_side_name(name, given.scan_frame)
           << " lies " << off << " mm from the model's skin (more than " << kGivenOffSkin
           << " mm): the file was placed on another scan or in another frame (a .mrk.json file is read in the scan's "
              "LPS or RAS frame, any other .json in the model's); correct the landmark file";
      throw Error("landmarks", text.str());
    }
  }
}

}  // namespace

std::map<std::string, double> feature_values(const ConstraintSet& standard) {
  std::map<std::string, double> values;
  for (const auto& c : standard.constraints) values[c.name] = c.value;
  return values;
}

ConstraintSet landmark_feature_constraints(const Eigen::MatrixXd& V, const Eigen::VectorXi& side_mask,
                                           const LandmarkOptions& landmark_options,
                                           const std::map<std::string, double>& values, double band,
                                           FaceLandmarks* landmarks_out, const FaceLandmarks* given) {
  FaceLandmarks landmarks = given ? *given : find_face_landmarks(V, side_mask, landmark_options);
  landmarks.scan_frame = landmark_options.scan_frame;
  // Given landmarks place the plane (through their pronasale); the model's own plane, where it has one, its lean,
  // turn and pitch.
  if (given && landmark_options.mid_sagittal_plane) {
    const MidSagittalPlane& own = *landmark_options.mid_sagittal_plane;
    const Eigen::Vector3d prn = landmarks.points.at("pronasale");
    landmarks.plane = MidSagittalPlane{prn.x(), own.slope, prn.z(), own.turn, prn.y(), own.pitch};
  }
  const std::string remedy = given ? "correct the landmark file" : "give the landmarks with --landmarks FILE";
  check_plausible(landmarks, remedy);
  if (given) check_on_skin(landmarks, V, side_mask);
  ConstraintSet set = feature_constraints(landmarks, values, band);
  for (Constraint& c : set.constraints) c.origin += "; " + remedy;
  if (landmarks_out) *landmarks_out = landmarks;
  return set;
}

ConstraintSet automatic_constraints(const Eigen::MatrixXd& V, const Eigen::VectorXi& side_mask,
                                    const LandmarkOptions& landmark_options,
                                    const std::map<std::string, double>& values, double band,
                                    FaceLandmarks* landmarks_out, const FaceLandmarks* given) {
  ConstraintSet set = side_constraints();
  for (Constraint& c :
       landmark_feature_constraints(V, side_mask, landmark_options, values, band, landmarks_out, given).constraints)
    set.constraints.push_back(std::move(c));
  return set;
}

}  // namespace facehex
