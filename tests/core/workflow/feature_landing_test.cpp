#include "core/workflow/feature_landing.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/mesh/head_turn.h"

namespace facehex {
namespace {

// A standard of three vertices: its stomion, its right cheilion and a vertex that is no landmark.
StandardFeatures three_vertex_standard() {
  StandardFeatures s;
  s.landmark_vertices = {{"stomion", 0}, {"cheilion right", 1}};
  return s;
}

TEST(FeatureLanding, TheDistanceAcrossTheFaceOfEachTransferredLandmarkFromThePatients) {
  const StandardFeatures standard = three_vertex_standard();
  FaceLandmarks patient;
  patient.plane.x = 0;
  patient.points["stomion"] = Eigen::Vector3d(0, 80, 10);
  patient.points["cheilion right"] = Eigen::Vector3d(-25, 70, 12);
  patient.points["nasion"] = Eigen::Vector3d(0, 90, 60);  // the standard has no vertex for it: left out
  patient.estimated = {"cheilion right"};
  Eigen::MatrixXd transferred(3, 3);
  transferred << 0, 75, 13,  // 3 mm above the stomion and 5 mm further back (in its slit): 3 mm across the face
      -21, 70, 9,            // 4 mm in x and 3 in z: 5 mm
      5, 5, 5;
  const std::vector<FeatureLanding> landing = feature_landing(standard, transferred, patient, {"stomion"});
  ASSERT_EQ(landing.size(), 2u);
  EXPECT_EQ(landing[0].name, "stomion");  // landmark_names() order: the profile first
  EXPECT_NEAR(landing[0].distance, 3.0, 1e-12);
  EXPECT_EQ(landing[0].patient_status, LandmarkStatus::found);
  EXPECT_EQ(landing[1].name, "cheilion right");
  EXPECT_NEAR(landing[1].distance, 5.0, 1e-12);
  EXPECT_EQ(landing[1].patient_status, LandmarkStatus::estimated);
  const nlohmann::json j = feature_landing_json(landing);
  EXPECT_NEAR(j["mean_mm"].get<double>(), 4.0, 1e-12);
  EXPECT_NEAR(j["max_mm"].get<double>(), 5.0, 1e-12);
  EXPECT_EQ(j["landmarks"][1]["patient"], "estimated");
  EXPECT_EQ(j["landmarks"][0]["pulled"], true);
  EXPECT_EQ(j["landmarks"][1]["pulled"], false);
  EXPECT_EQ(j["landmarks"][1]["landed"], nlohmann::json({-21.0, 70.0, 9.0}));
  EXPECT_EQ(j["landmarks"][1]["patient_at"], nlohmann::json({-25.0, 70.0, 12.0}));
  EXPECT_EQ(feature_landing_text(landing),
            "anatomy: the standard's 2 landmarks land 4.0 mm across the face from the patient's on average (3.0 mm "
            "at the 1 not estimated), farthest cheilion right 5.0 mm; not pulled: cheilion right\n");
  // None pulled (the pull off, or the feature lines): nothing to single out.
  EXPECT_EQ(feature_landing_text(feature_landing(standard, transferred, patient)),
            "anatomy: the standard's 2 landmarks land 4.0 mm across the face from the patient's on average (3.0 mm "
            "at the 1 not estimated), farthest cheilion right 5.0 mm\n");
}

TEST(FeatureLanding, ATurnedHeadIsMeasuredInItsHeadFrame) {
  // The patient's head turned 30 degrees: a transferred landmark 4 mm in front of the patient's along the face's own
  // front direction lies on it across the face.
  const StandardFeatures standard = three_vertex_standard();
  FaceLandmarks patient;
  patient.plane.turn = std::tan(30 * M_PI / 180);
  patient.points["stomion"] = Eigen::Vector3d(0, 80, 10);
  const Eigen::Vector3d forward = head_turn_of(patient.plane).to_model(Eigen::Vector3d(0, 1, 0)) -
                                  head_turn_of(patient.plane).to_model(Eigen::Vector3d::Zero());
  Eigen::MatrixXd transferred = Eigen::MatrixXd::Zero(3, 3);
  transferred.row(0) = (patient.points["stomion"] + 4 * forward).transpose();
  const std::vector<FeatureLanding> landing = feature_landing(standard, transferred, patient);
  ASSERT_EQ(landing.size(), 1u);
  EXPECT_NEAR(landing[0].distance, 0.0, 1e-9);
}

TEST(FeatureLanding, NoLandmarksInCommonIsNothingToReport) {
  EXPECT_TRUE(feature_landing(three_vertex_standard(), Eigen::MatrixXd::Zero(3, 3), FaceLandmarks{}).empty());
  EXPECT_TRUE(feature_landing_json({}).is_null());
  EXPECT_EQ(feature_landing_text({}), "");
}

}  // namespace
}  // namespace facehex
