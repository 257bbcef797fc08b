#pragma once
// Where a transfer put the standard's facial features on the patient, for people to judge the anatomy first: for
// each landmark the standard has as a vertex (core/standard/standard_features.h: its profile's landmarks and the
// corners of its open eyes and mouth) and the patient has, how far across the face that vertex's transferred position
// lies from the patient's landmark: the distance in x and z of the head frame of the patient's mid-sagittal plane
// (core/mesh/head_turn.h), leaving out the depth, since a landmark in a closed slit (a CT's eye corners and stomion)
// lies a few millimetres behind the open standard's rim at the same place. The patient's landmarks are those its
// feature constraints were placed at (found, estimated or given). The tragi lie off the standard.
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/face/face_landmarks.h"
#include "core/face/landmark_file.h"
#include "core/standard/standard_features.h"

namespace facehex {

struct FeatureLanding {
  std::string name;     // the patient's side for a paired landmark (core/mesh/scan_frame.h)
  double distance = 0;  // mm, across the face
  LandmarkStatus patient_status = LandmarkStatus::found;
  Eigen::Vector3d landed = Eigen::Vector3d::Zero();   // the standard's landmark where the transfer put it (mm)
  Eigen::Vector3d patient = Eigen::Vector3d::Zero();  // the patient's landmark (mm)
  bool pulled = false;  // the landmark pulled the skin's registration (core/workflow/transfer.h)
};

// transferred: the transferred standard's vertices (#V x 3, the standard's vertex order); pulled: the names of the
// landmarks that pulled the registration. In landmark_names() order.
std::vector<FeatureLanding> feature_landing(const StandardFeatures& standard, const Eigen::MatrixXd& transferred,
                                            const FaceLandmarks& patient, const std::vector<std::string>& pulled = {});

// {"mean_mm", "max_mm", "landmarks": [{"name", "mm", "patient": "found" | "estimated" | "given", "pulled": bool,
// "landed": [x, y, z], "patient_at": [x, y, z]}, ...]}; null when there is none.
nlohmann::json feature_landing_json(const std::vector<FeatureLanding>& landing);
// "anatomy: the standard's 13 landmarks land 1.4 mm across the face from the patient's on average (1.2 mm at the 9
// not estimated), farthest exocanthion left 3.1 mm\n", with "; not pulled: cheilion right" before the newline when some
// landmarks pulled and others did not; or empty.
std::string feature_landing_text(const std::vector<FeatureLanding>& landing);

}  // namespace facehex
