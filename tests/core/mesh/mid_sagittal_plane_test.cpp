#include "core/mesh/mid_sagittal_plane.h"

#include <gtest/gtest.h>

#include <limits>
#include <sstream>

#include "tests/core/io/io_test_util.h"

namespace facehex {
namespace {

TEST(MidSagittalPlane, SetThenReadBack) {
  VolumeMesh mesh;
  EXPECT_FALSE(mid_sagittal_plane(mesh, "model.vtu"));
  set_mid_sagittal_plane(mesh, {98.37, -0.05, 80});
  const std::optional<MidSagittalPlane> plane = mid_sagittal_plane(mesh, "model.vtu");
  ASSERT_TRUE(plane);
  EXPECT_EQ(plane->x, 98.37);
  EXPECT_EQ(plane->slope, -0.05);
  EXPECT_EQ(plane->z, 80);
  EXPECT_DOUBLE_EQ(plane->x_at(0, 100), 98.37 - 1.0);
}

TEST(MidSagittalPlane, ATurnedPlaneKeepsItsTurnAndAnUnturnedOneThreeNumbers) {
  VolumeMesh mesh;
  MidSagittalPlane turned;
  turned.x = 98, turned.slope = 0.02, turned.z = 80, turned.turn = -0.17, turned.y = 60;
  set_mid_sagittal_plane(mesh, turned);
  EXPECT_EQ(mesh.field_data.at(kMidSagittalPlaneField).cols(), 5);
  const std::optional<MidSagittalPlane> back = mid_sagittal_plane(mesh, "model.vtu");
  ASSERT_TRUE(back);
  EXPECT_EQ(back->turn, -0.17);
  EXPECT_EQ(back->y, 60);
  EXPECT_DOUBLE_EQ(back->x_at(70, 80), 98 - 1.7);
  set_mid_sagittal_plane(mesh, {98, 0.02, 80});
  EXPECT_EQ(mesh.field_data.at(kMidSagittalPlaneField).cols(), 3);
}

TEST(MidSagittalPlane, APitchedHeadsPlaneKeepsItsPitchInASixthNumber) {
  VolumeMesh mesh;
  MidSagittalPlane pitched;
  pitched.x = 98, pitched.slope = 0.02, pitched.z = 80, pitched.y = 60, pitched.pitch = -12.5;
  set_mid_sagittal_plane(mesh, pitched);
  EXPECT_EQ(mesh.field_data.at(kMidSagittalPlaneField).cols(), 6);
  const std::optional<MidSagittalPlane> back = mid_sagittal_plane(mesh, "model.vtu");
  ASSERT_TRUE(back);
  EXPECT_EQ(back->pitch, -12.5);
  EXPECT_EQ(back->turn, 0);
  EXPECT_EQ(back->y, 60);
  EXPECT_NE(mid_sagittal_plane_text(*back).find("pitched -12.5 degrees"), std::string::npos);
}

TEST(MidSagittalPlane, MalformedFieldDataIsAnErrorNamingTheFile) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Eigen::MatrixXd& bad : {Eigen::MatrixXd(0, 3), Eigen::MatrixXd(Eigen::MatrixXd::Constant(1, 1, 98.0)),
                                     Eigen::MatrixXd((Eigen::MatrixXd(1, 3) << 98, nan, 80).finished()),
                                     Eigen::MatrixXd((Eigen::MatrixXd(1, 3) << 98, 2.0, 80).finished()),
                                     Eigen::MatrixXd((Eigen::MatrixXd(1, 4) << 98, 0, 80, 0.2).finished()),
                                     Eigen::MatrixXd((Eigen::MatrixXd(1, 5) << 98, 0, 80, 1.5, 60).finished()),
                                     Eigen::MatrixXd((Eigen::MatrixXd(1, 6) << 98, 0, 80, 0, 60, 50).finished()),
                                     Eigen::MatrixXd((Eigen::MatrixXd(1, 6) << 98, 0, 80, 0, 60, nan).finished())}) {
    VolumeMesh mesh;
    mesh.field_data[kMidSagittalPlaneField] = bad;
    std::ostringstream given;
    given << bad;
    test::expect_error([&] { mid_sagittal_plane(mesh, "model.vtu"); }, "model.vtu: the field data 'mid_sagittal_plane'",
                       given.str());
  }
}

}  // namespace
}  // namespace facehex
