#include "core/face/automatic_constraints.h"

#include <utility>

namespace facehex {

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
  // Given landmarks place the plane (through their pronasale); the model's own plane, where it has one, its lean,
  // turn and pitch.
  if (given && landmark_options.mid_sagittal_plane) {
    const MidSagittalPlane& own = *landmark_options.mid_sagittal_plane;
    const Eigen::Vector3d prn = landmarks.points.at("pronasale");
    landmarks.plane = MidSagittalPlane{prn.x(), own.slope, prn.z(), own.turn, prn.y(), own.pitch};
  }
  const std::string remedy = given ? "correct the landmark file" : "give the landmarks with --landmarks FILE";
  check_plausible(landmarks, remedy);
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
