#include "core/mesh/tragi.h"

#include <gtest/gtest.h>

#include <limits>

#include "tests/core/io/io_test_util.h"

namespace facehex {
namespace {

TEST(Tragi, SetThenReadBackWithAnUnseenSide) {
  VolumeMesh mesh;
  EXPECT_FALSE(tragi(mesh, "model.vtu"));
  Tragi given;
  given[1] = Tragus{Eigen::Vector3d(331.1, 276.0, 89.3), true};
  set_tragi(mesh, given);
  const std::optional<Tragi> back = tragi(mesh, "model.vtu");
  ASSERT_TRUE(back);
  EXPECT_FALSE((*back)[0]);
  ASSERT_TRUE((*back)[1]);
  EXPECT_EQ((*back)[1]->point, given[1]->point);
  EXPECT_TRUE((*back)[1]->estimated);
}

TEST(Tragi, MalformedFieldDataIsAnErrorNamingTheFileAndTheArray) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Eigen::MatrixXd wrong_shape = Eigen::MatrixXd::Zero(2, 3);
  const Eigen::MatrixXd partly_nan = (Eigen::MatrixXd(2, 4) << 1, 2, 3, 0, 4, nan, 6, 0).finished();
  const Eigen::MatrixXd bad_status = (Eigen::MatrixXd(2, 4) << 1, 2, 3, 0, 4, 5, 6, 2).finished();
  for (const auto& [bad, problem] :
       {std::pair{wrong_shape, "is 2 x 3"}, std::pair{partly_nan, "numbers that are not finite"},
        std::pair{bad_status, "a status that is neither 0 nor 1"}}) {
    VolumeMesh mesh;
    mesh.field_data[kTragiField] = bad;
    test::expect_error([&] { tragi(mesh, "model.vtu"); }, "model.vtu: the field data 'tragi'");
    test::expect_error([&] { tragi(mesh, "model.vtu"); }, problem);
  }
}

}  // namespace
}  // namespace facehex
