#include "core/mesh/scan_frame.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <limits>

#include "tests/core/io/io_test_util.h"

namespace facehex {
namespace {

// A DICOM-like frame: the model's axes a half turn about z from the scan's LPS axes, and an offset.
ScanFrame half_turn() {
  ScanFrame f;
  f.rotation = Eigen::Vector3d(-1, -1, 1).asDiagonal();
  f.translation = Eigen::Vector3d(250, 250, -40);
  return f;
}

TEST(ScanFrame, AModelWithoutOneIsInItsOwnFrameAndNamesItsSidesAsThePatients) {
  const ScanFrame f = scan_frame(VolumeMesh(), "model.vtu");
  EXPECT_EQ(f.to_scan(Eigen::Vector3d(1, 2, 3)), Eigen::Vector3d(1, 2, 3));
  EXPECT_FALSE(f.left_at_minus_x());
  EXPECT_EQ(patient_side_name("exocanthion left", f), "exocanthion left");
}

TEST(ScanFrame, SetThenReadBackMapsPointsBothWays) {
  VolumeMesh mesh;
  const ScanFrame f = half_turn();
  set_scan_frame(mesh, f);
  const ScanFrame back = scan_frame(mesh, "model.vtu");
  EXPECT_TRUE(back.rotation.isApprox(f.rotation));
  EXPECT_TRUE(back.translation.isApprox(f.translation));
  const Eigen::Vector3d p(10, -20, 30);
  EXPECT_TRUE(back.to_scan(p).isApprox(Eigen::Vector3d(240, 270, -10)));
  EXPECT_TRUE(back.from_scan(back.to_scan(p)).isApprox(p));
}

TEST(ScanFrame, AfterTheModelMovesTheSamePointsLieAtTheSameScanPoints) {
  const ScanFrame f = half_turn();
  const Eigen::Matrix3d A = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d b(5, -6, 7);
  const ScanFrame moved = f.after_model_change(A, b);
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(10, -20, 30)})
    EXPECT_TRUE(moved.to_scan(A * p + b).isApprox(f.to_scan(p))) << p.transpose();
}

TEST(ScanFrame, PairedNamesSayTheirSideAndNameTheirPartner) {
  EXPECT_EQ(named_side("cheilion left"), 1);
  EXPECT_EQ(named_side("tragus right"), -1);
  EXPECT_EQ(named_side("pronasale"), 0);
  EXPECT_EQ(named_side("left"), 0);  // a suffix, not a name
  EXPECT_EQ(other_side_name("endocanthion left"), "endocanthion right");
  EXPECT_EQ(other_side_name("tragus right"), "tragus left");
  EXPECT_EQ(other_side_name("menton"), "menton");
}

TEST(ScanFrame, PairedNamesSwapWhereThePatientsLeftIsAtMinusX) {
  const ScanFrame f = half_turn();
  EXPECT_TRUE(f.left_at_minus_x());
  EXPECT_EQ(patient_side_name("exocanthion left", f), "exocanthion right");
  EXPECT_EQ(patient_side_name("cheilion right", f), "cheilion left");
  EXPECT_EQ(patient_side_name("tragus left", f), "tragus right");
  EXPECT_EQ(patient_side_name("pronasale", f), "pronasale");
  for (const char* name : {"endocanthion left", "tragus right", "menton"})
    EXPECT_EQ(patient_side_name(patient_side_name(name, f), f), name);  // its own inverse
  // A mirror that keeps x (a NIfTI file stored with its rows flipped front to back) keeps the names.
  ScanFrame mirror;
  mirror.rotation = Eigen::Vector3d(1, -1, 1).asDiagonal();
  EXPECT_EQ(patient_side_name("exocanthion left", mirror), "exocanthion left");
}

TEST(ScanFrame, TextSaysWhereThePatientsLeftIsAndHowTheAxesMap) {
  EXPECT_EQ(
      scan_frame_text(half_turn()),
      "the patient's left at -x of the model; model (x, y, z) at scan (-x + 250.0, -y + 250.0, z - 40.0) mm (LPS)");
  EXPECT_EQ(scan_frame_text(ScanFrame()),
            "the patient's left at +x of the model; model (x, y, z) at scan (x, y, z) mm (LPS)");
  ScanFrame oblique;
  oblique.rotation = Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_NE(scan_frame_text(oblique).find("R rows (0.995, -0.100, 0.000) (0.100, 0.995, 0.000)"), std::string::npos)
      << scan_frame_text(oblique);
}

TEST(ScanFrame, MalformedFieldDataIsAnErrorNamingTheFileAndTheArray) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Eigen::MatrixXd sheared(3, 4);
  sheared << 1, 0.5, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0;
  Eigen::MatrixXd with_nan = Eigen::MatrixXd::Identity(3, 4);
  with_nan(1, 3) = nan;
  for (const Eigen::MatrixXd& bad : {Eigen::MatrixXd(Eigen::MatrixXd::Identity(3, 3)), sheared, with_nan}) {
    VolumeMesh mesh;
    mesh.field_data[kScanFrameField] = bad;
    test::expect_error([&] { scan_frame(mesh, "model.vtu"); }, "model.vtu: the field data 'scan_frame'");
  }
}

}  // namespace
}  // namespace facehex
