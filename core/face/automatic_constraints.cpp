#include "core/face/automatic_constraints.h"

namespace facehex {

std::map<std::string, double> feature_values(const ConstraintSet& standard) {
  std::map<std::string, double> values;
  for (const auto& c : standard.constraints) values[c.name] = c.value;
  return values;
}

ConstraintSet automatic_constraints(const Eigen::MatrixXd& V, const Eigen::VectorXi& side_mask,
                                    const std::map<std::string, double>& values, double band,
                                    FaceLandmarks* landmarks_out, const FaceLandmarks* given) {
  const FaceLandmarks landmarks = given ? *given : find_face_landmarks(V, side_mask);
  const std::string remedy = given ? "correct the landmark file" : "give the landmarks with --landmarks FILE";
  check_plausible(landmarks, remedy);
  ConstraintSet set = side_constraints();
  for (auto& c : feature_constraints(landmarks, values, band).constraints) {
    c.origin += "; " + remedy;
    set.constraints.push_back(c);
  }
  if (landmarks_out) *landmarks_out = landmarks;
  return set;
}

}  // namespace facehex
