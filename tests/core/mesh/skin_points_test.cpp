#include "core/mesh/skin_points.h"

#include <gtest/gtest.h>

#include <limits>
#include <sstream>

#include "tests/core/io/io_test_util.h"

namespace facehex {
namespace {

TEST(SkinPoints, SetThenReadBack) {
  VolumeMesh mesh;
  EXPECT_FALSE(skin_points(mesh, "model.vtu"));
  const Eigen::MatrixXd points = (Eigen::MatrixXd(2, 3) << 1, 2, 3, 4.5, 5.5, 6.5).finished();
  set_skin_points(mesh, points);
  const std::optional<Eigen::MatrixXd> back = skin_points(mesh, "model.vtu");
  ASSERT_TRUE(back);
  EXPECT_EQ(*back, points);
}

TEST(SkinPoints, MalformedFieldDataIsAnErrorNamingTheFileAndTheArray) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Eigen::MatrixXd& bad : {Eigen::MatrixXd(0, 3), Eigen::MatrixXd(Eigen::MatrixXd::Constant(4, 2, 1.0)),
                                     Eigen::MatrixXd((Eigen::MatrixXd(2, 3) << 1, 2, 3, 4, nan, 6).finished())}) {
    VolumeMesh mesh;
    mesh.field_data[kSkinPointsField] = bad;
    std::ostringstream given;
    given << bad;
    test::expect_error([&] { skin_points(mesh, "model.vtu"); }, "model.vtu: the field data 'skin_points'", given.str());
  }
}

}  // namespace
}  // namespace facehex
