// The numbers of `facehex compare` against a hand computation on one cube, and the PNG histograms.
#include "app/commands/compare.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "app/histogram_png.h"
#include "core/mesh/hex_to_tets.h"
#include "core/util/error.h"
#include "tests/core/test_meshes.h"

namespace facehex::cli {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The unit cube mapped by x' = x + tan(20 deg) y, y' = y, z' = 2 z. By hand: its four edges along z lie between a
// face x = const (spanned by (k, 1, 0) and z) and a face y = const (spanned by x and z), so their dihedral angles
// become 90 -/+ 20 degrees (the angle between (1, 0, 0) and (k, 1, 0) is atan(1 / k) = 70 degrees); the eight other
// edges join a z face, which stays perpendicular to the others: 0 change. Every corner has the Jacobian
// A = [[1, k, 0], [0, 1, 0], [0, 0, 2]]: Knupp shape 3 det(A)^(2/3) / |A|_F^2 = 3 * 2^(2/3) / (6 + k^2); scaled
// Jacobian det(A) / (1 * sqrt(1 + k^2) * 2) = cos(20 deg).
TEST(CompareMetrics, ShearedCubeMatchesTheHandComputation) {
  const VolumeMesh standard = test::hex_box(1, 1, 1);
  const double k = std::tan(20 * kPi / 180);
  VolumeMesh mapped = standard;
  mapped.V.col(0) += k * standard.V.col(1);
  mapped.V.col(2) *= 2;
  const Eigen::MatrixXi T = split_into_tets(mapped).T;  // the patient is the mapped cube itself
  const MethodMetrics m = method_metrics(standard, mapped, mapped.V, T, {{"first", 1.5}, {"second", 0.25}});
  const nlohmann::json j = to_json(m);

  const std::vector<double> bins = j["dihedral_bins_percent"];
  const std::vector<double> expected_bins = {800.0 / 12, 0, 400.0 / 12, 0, 0, 0};  // 8 edges 0 deg, 4 edges 20 deg
  ASSERT_EQ(bins.size(), expected_bins.size());
  for (size_t b = 0; b < bins.size(); ++b) EXPECT_NEAR(bins[b], expected_bins[b], 1e-9) << "bin " << b;
  EXPECT_NEAR(j["dihedral_max"].get<double>(), 20.0, 1e-9);
  EXPECT_NEAR(j["dihedral_mean"].get<double>(), 4 * 20.0 / 12, 1e-9);
  EXPECT_NEAR(j["shape_mean"].get<double>(), 3 * std::cbrt(4.0) / (6 + k * k), 1e-9);
  EXPECT_NEAR(j["shape_min"].get<double>(), 3 * std::cbrt(4.0) / (6 + k * k), 1e-9);
  EXPECT_NEAR(j["scaled_jacobian_min"].get<double>(), std::cos(20 * kPi / 180), 1e-9);
  EXPECT_EQ(j["inverted"], 0);
  EXPECT_EQ(j["degenerate"], 0);
  EXPECT_LT(j["side_vertex_distance_mm"]["max"].get<double>(), 1e-9);  // all 8 corners on the patient's boundary
  EXPECT_NEAR(j["seconds"].get<double>(), 1.75, 1e-12);
  EXPECT_EQ(j["stages"]["second"], 0.25);
  // The histogram data behind it: one shape per cell, one change per cell edge.
  ASSERT_EQ(m.dihedral_changes.size(), 12);
  EXPECT_EQ((m.dihedral_changes.array() > 19.999).count(), 4);
  ASSERT_EQ(m.shape.size(), 1);
}

TEST(CompareMetrics, SideDistanceIsMeasuredToThePatientsBoundary) {
  // The patient is the cube moved 0.3 along +x: the corners at x = 0 are 0.3 off its surface, those at x = 1 on it.
  const VolumeMesh standard = test::hex_box(1, 1, 1);
  Eigen::MatrixXd patient_V = standard.V;
  patient_V.col(0).array() += 0.3;
  const MethodMetrics m = method_metrics(standard, standard, patient_V, split_into_tets(standard).T, {});
  EXPECT_NEAR(m.side_distance.max, 0.3, 1e-9);
  EXPECT_NEAR(m.side_distance.mean, 0.15, 1e-9);
  EXPECT_EQ(m.side_distance.points, 8);
}

TEST(HistogramPng, PercentPerBinWithOpenEnds) {
  Eigen::VectorXd values(5);
  values << -1, 0.5, 1.5, 1.6, 99;
  const std::vector<double> p = percent_histogram(values, {0, 1, 2});
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p[0], 40, 1e-12);  // -1 and 0.5
  EXPECT_NEAR(p[1], 60, 1e-12);  // 1.5, 1.6 and 99
}

TEST(HistogramPng, WritesAPngAndRejectsMismatchedSeries) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("facehex-hist-" + std::to_string(::getpid()) + ".png")).string();
  HistogramPlot plot;
  plot.title = "test";
  plot.x_label = "x";
  plot.edges = {0, 1, 2, 3};
  plot.series = {{"a", {255, 0, 0}, {10, 50, 40}}, {"b", {0, 0, 255}, {30, 30, 40}}};
  write_histogram_png(path, plot);
  std::ifstream in(path, std::ios::binary);
  char signature[8] = {};
  in.read(signature, 8);
  EXPECT_EQ(std::string(signature + 1, 3), "PNG");
  std::filesystem::remove(path);
  plot.series[1].percent.pop_back();
  EXPECT_THROW(write_histogram_png(path, plot), Error);
  EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace facehex::cli
