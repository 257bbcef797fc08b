#include "core/mesh/ct_landmarks.h"

#include <gtest/gtest.h>

#include <limits>

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
  set_ct_landmarks(mesh, given);
  EXPECT_EQ(mesh.field_data.at(kCtLandmarksField).rows(), 7);
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
}

TEST(CtLandmarks, MalformedFieldDataIsAnErrorNamingTheFileAndTheArray) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Eigen::MatrixXd wrong_shape = Eigen::MatrixXd::Zero(2, 4);
  Eigen::MatrixXd partly_nan = Eigen::MatrixXd::Constant(7, 4, nan);
  partly_nan.row(3) << 4, nan, 6, 0;
  Eigen::MatrixXd bad_status = Eigen::MatrixXd::Zero(7, 4);
  bad_status(5, 3) = 2;
  for (const auto& [bad, problem] :
       {std::pair{wrong_shape, "is 2 x 4"}, std::pair{partly_nan, "numbers that are not finite"},
        std::pair{bad_status, "a status that is neither 0 nor 1"}}) {
    VolumeMesh mesh;
    mesh.field_data[kCtLandmarksField] = bad;
    test::expect_error([&] { ct_landmarks(mesh, "model.vtu"); }, "model.vtu: the field data 'ct_landmarks'");
    test::expect_error([&] { ct_landmarks(mesh, "model.vtu"); }, problem);
  }
}

}  // namespace
}  // namespace facehex
