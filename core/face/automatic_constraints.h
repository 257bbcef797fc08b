#pragma once
// The constraint set FaceHex places by itself on a model with side labels: the six sides (the fields' ends, paper
// 3.2) and the feature constraints at the model's facial landmarks (paper 3.4, face_landmarks.h), valued as the
// standard's features of the same names so that the patient's nose lands where the standard's is. `facehex run` and
// `facehex constraints` use it, and the desktop application gives it to a patient when it opens.
#include <Eigen/Core>
#include <map>
#include <string>

#include "core/face/face_landmarks.h"
#include "core/fields/constraint_set.h"

namespace facehex {

constexpr double kFeatureBand = 2.0;  // mm, width of the slabs selecting feature vertices

// The value of each constraint of a standard's set, by constraint name.
std::map<std::string, double> feature_values(const ConstraintSet& standard);

// The feature constraints alone at the landmarks of the model (V #V x 3, side_mask #V), with the given feature
// values: at `given` landmarks (the user's), else at those find_face_landmarks finds with `landmark_options`. Either
// set must pass check_plausible, and given ones on the skin (all but the tragi) must lie within 10 mm of it. Given
// landmarks have their mid-sagittal plane through their pronasale, leaning and
// turned as landmark_options' plane when it has one (a segmented CT's: a turned head's given landmarks lie on a turned
// plane), else vertical and unturned. `landmarks_out` receives where they were placed. Throws
// facehex::Error("landmarks", ...) when a landmark is not found or the set is implausible (naming the landmark and
// --landmarks FILE), and facehex::Error("feature constraints", ...) when a feature has no value.
ConstraintSet landmark_feature_constraints(const Eigen::MatrixXd& V, const Eigen::VectorXi& side_mask,
                                           const LandmarkOptions& landmark_options,
                                           const std::map<std::string, double>& values, double band = kFeatureBand,
                                           FaceLandmarks* landmarks_out = nullptr,
                                           const FaceLandmarks* given = nullptr);

// The six sides plus landmark_feature_constraints, with the same arguments and errors.
ConstraintSet automatic_constraints(const Eigen::MatrixXd& V, const Eigen::VectorXi& side_mask,
                                    const LandmarkOptions& landmark_options,
                                    const std::map<std::string, double>& values, double band = kFeatureBand,
                                    FaceLandmarks* landmarks_out = nullptr, const FaceLandmarks* given = nullptr);

}  // namespace facehex
