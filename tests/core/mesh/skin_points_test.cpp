#include "core/mesh/skin_points.h"

#include <gtest/gtest.h>

#include <limits>

#include "core/util/error.h"

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
    try {
      skin_points(mesh, "model.vtu");
      ADD_FAILURE() << "accepted " << bad;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("model.vtu"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("skin_points"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace facehex
