#include "core/mesh/mid_sagittal_plane.h"

#include <gtest/gtest.h>

#include <limits>

#include "core/util/error.h"

namespace facehex {
namespace {

TEST(MidSagittalPlane, SetThenReadBack) {
  VolumeMesh mesh;
  EXPECT_FALSE(mid_sagittal_x(mesh, "model.vtu"));
  set_mid_sagittal_x(mesh, 98.37);
  EXPECT_EQ(mid_sagittal_x(mesh, "model.vtu"), 98.37);
}

TEST(MidSagittalPlane, MalformedFieldDataIsAnErrorNamingTheFile) {
  for (const Eigen::MatrixXd& bad :
       {Eigen::MatrixXd(0, 1), Eigen::MatrixXd(Eigen::MatrixXd::Constant(2, 1, 1.0)),
        Eigen::MatrixXd(Eigen::MatrixXd::Constant(1, 1, std::numeric_limits<double>::quiet_NaN()))}) {
    VolumeMesh mesh;
    mesh.field_data[kMidSagittalXField] = bad;
    try {
      mid_sagittal_x(mesh, "model.vtu");
      ADD_FAILURE() << "accepted " << bad.rows() << " x " << bad.cols();
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("model.vtu"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("mid_sagittal_x"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace facehex
