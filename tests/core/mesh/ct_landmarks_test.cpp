#include "core/mesh/ct_landmarks.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include "tests/core/io/io_test_util.h"

namespace facehex {
namespace {

TEST(CtLandmarks, SetThenReadBackWithUnseenOnes) {
  VolumeMesh mesh;
  EXPECT_FALSE(ct_landmarks(mesh, "model.vtu"));
  CtLandmarks given;
  given.tragi[1] = CtLandmark{Eigen::Vector3d(331.1, 276.0, 89.3), true};
  given.eye_corners[2] = CtLandmark{Eigen::Vector3d(276.4, 344.3, 135.2), false};
  given.stomion = CtLandmark{Eigen::Vector3d(263.1, 372.9, 59.0), false};
  given.mouth_corners[1] = CtLandmark{Eigen::Vector3d(293.4, 360.9, 57.2), false};
  given.bony_menton = CtLandmark{Eigen::Vector3d(261.8, 353.0, 22.0), false};
  set_ct_landmarks(mesh, given);
  EXPECT_EQ(mesh.field_data.at(kCtLandmarksField).rows(), 10);
  const std::optional<CtLandmarks> back = ct_landmarks(mesh, "model.vtu");
  ASSERT_TRUE(back);
  EXPECT_FALSE(back->tragi[0]);
  ASSERT_TRUE(back->tragi[1]);
  EXPECT_EQ(back->tragi[1]->point, given.tragi[1]->point);
  EXPECT_TRUE(back->tragi[1]->estimated);
  for (int c : {0, 1, 3}) EXPECT_FALSE(back->eye_corners[c]);
  ASSERT_TRUE(back->eye_corners[2]);
  EXPECT_EQ(back->eye_corners[2]->point, given.eye_corners[2]->point);
  EXPECT_FALSE(back->eye_corners[2]->estimated);
  ASSERT_TRUE(back->stomion);
  EXPECT_EQ(back->stomion->point, given.stomion->point);
  EXPECT_FALSE(back->mouth_corners[0]);
  ASSERT_TRUE(back->mouth_corners[1]);
  EXPECT_EQ(back->mouth_corners[1]->point, given.mouth_corners[1]->point);
  ASSERT_TRUE(back->bony_menton);
  EXPECT_EQ(back->bony_menton->point, given.bony_menton->point);
}

TEST(CtLandmarks, ATableOfTheFirstRowsOnlyIsReadWithoutTheOthers) {
  // A model written with the first seven or nine rows only: its landmarks read, the later ones not seen.
  CtLandmarks given;
  given.stomion = CtLandmark{Eigen::Vector3d(263.1, 372.9, 59.0), false};
  given.mouth_corners[0] = CtLandmark{Eigen::Vector3d(223.6, 353.3, 55.8), false};
  given.bony_menton = CtLandmark{Eigen::Vector3d(261.8, 353.0, 22.0), false};
  for (const int rows : {7, 9}) {
    VolumeMesh mesh;
    set_ct_landmarks(mesh, given);
    Eigen::MatrixXd& table = mesh.field_data.at(kCtLandmarksField);
    table = table.topRows(rows).eval();
    const std::optional<CtLandmarks> back = ct_landmarks(mesh, "model.vtu");
    ASSERT_TRUE(back);
    ASSERT_TRUE(back->stomion);
    EXPECT_EQ(back->stomion->point, given.stomion->point);
    EXPECT_EQ(back->mouth_corners[0].has_value(), rows == 9);
    EXPECT_FALSE(back->bony_menton);
  }
}

TEST(CtLandmarks, MalformedFieldDataIsAnErrorNamingTheFileAndTheArray) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Eigen::MatrixXd wrong_shape = Eigen::MatrixXd::Zero(11, 4);
  Eigen::MatrixXd partly_nan = Eigen::MatrixXd::Constant(10, 4, nan);
  partly_nan.row(3) << 4, nan, 6, 0;
  Eigen::MatrixXd bad_status = Eigen::MatrixXd::Zero(7, 4);
  bad_status(5, 3) = 2;
  for (const auto& [bad, problem] :
       {std::pair{wrong_shape, "is 11 x 4"}, std::pair{partly_nan, "numbers that are not finite"},
        std::pair{bad_status, "a status that is neither 0 nor 1"}}) {
    VolumeMesh mesh;
    mesh.field_data[kCtLandmarksField] = bad;
    test::expect_error([&] { ct_landmarks(mesh, "model.vtu"); }, "model.vtu: the field data 'ct_landmarks'");
    test::expect_error([&] { ct_landmarks(mesh, "model.vtu"); }, problem);
  }
}

TEST(CtLandmarks, SkinObjectsAndTheSkinUnderThemReadBack) {
  VolumeMesh mesh;
  CtLandmarks given;
  given.skin_objects = {{150, 170, 4.1, 3.9, {{145, 368.2}, {150, 368.4}, {175, 363.1}}}, {180, 190, 2.5, 2.6, {}}};
  given.skin_objects[1].skin = {{175, 363.0}, {195, 355.5}};
  set_ct_landmarks(mesh, given);
  EXPECT_EQ(mesh.field_data.at(kSkinObjectsField).rows(), 2);
  EXPECT_EQ(mesh.field_data.at(kSkinUnderObjectsField).rows(), 5);
  const std::optional<CtLandmarks> back = ct_landmarks(mesh, "model.vtu");
  ASSERT_TRUE(back);
  ASSERT_EQ(back->skin_objects.size(), 2u);
  for (size_t o = 0; o < 2; ++o) {
    EXPECT_EQ(back->skin_objects[o].z_low, given.skin_objects[o].z_low);
    EXPECT_EQ(back->skin_objects[o].z_high, given.skin_objects[o].z_high);
    EXPECT_EQ(back->skin_objects[o].thickness_low, given.skin_objects[o].thickness_low);
    EXPECT_EQ(back->skin_objects[o].thickness_high, given.skin_objects[o].thickness_high);
    EXPECT_EQ(back->skin_objects[o].skin, given.skin_objects[o].skin);
  }
  given.skin_objects.clear();  // set again without: none left behind
  set_ct_landmarks(mesh, given);
  EXPECT_FALSE(mesh.field_data.count(kSkinObjectsField) || mesh.field_data.count(kSkinUnderObjectsField));
  EXPECT_TRUE(ct_landmarks(mesh, "model.vtu")->skin_objects.empty());
}

TEST(CtLandmarks, MalformedSkinObjectsAreAnErrorNamingTheArrayAndHowToLeaveThemOut) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Eigen::MatrixXd good_object(1, 4), good_skin(2, 3);
  good_object << 150, 170, 4, 4;
  good_skin << 0, 145, 368, 0, 175, 363;
  Eigen::MatrixXd upside_down = good_object, no_thickness = good_object, not_finite = good_object;
  upside_down(0, 1) = 140;
  no_thickness(0, 3) = 0;
  not_finite(0, 2) = nan;
  Eigen::MatrixXd other_object = good_skin, not_increasing = good_skin, one_point = good_skin.topRows(1);
  other_object(1, 0) = 1;
  not_increasing(1, 1) = 140;
  const std::vector<std::tuple<Eigen::MatrixXd, Eigen::MatrixXd, std::string>> cases = {
      {Eigen::MatrixXd::Zero(1, 3), good_skin, "skin_objects"},
      {upside_down, good_skin, "skin_objects"},
      {no_thickness, good_skin, "skin_objects"},
      {not_finite, good_skin, "skin_objects"},
      {good_object, other_object, "skin_under_objects"},
      {good_object, not_increasing, "skin_under_objects"},
      {good_object, one_point, "skin_under_objects"},
      {good_object, Eigen::MatrixXd(0, 3), "skin_under_objects"}};
  for (const auto& [objects, skin, name] : cases) {
    VolumeMesh mesh;
    set_ct_landmarks(mesh, CtLandmarks{});
    mesh.field_data[kSkinObjectsField] = objects;
    if (skin.rows() > 0) mesh.field_data[kSkinUnderObjectsField] = skin;
    test::expect_error([&] { ct_landmarks(mesh, "model.vtu"); }, "model.vtu: the field data '" + name + "'");
    test::expect_error([&] { ct_landmarks(mesh, "model.vtu"); }, "to have them left out");
  }
}

}  // namespace
}  // namespace facehex
