#include "core/mapping/hex_transfer.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <limits>
#include <random>
#include <vector>

#include "core/fields/harmonic_fields.h"
#include "core/mapping/param_locator.h"
#include "core/mapping/transfer_pipeline.h"
#include "core/mesh/hex_to_tets.h"
#include "core/util/error.h"
#include "tests/core/test_meshes.h"

namespace facehex {
namespace {

TEST(ParamLocator, FindsTheContainingTetAndReproducesThePoint) {
  VolumeMesh hex = test::hex_box(4, 4, 4);
  test::jitter_interior(hex, 0.05);
  const Eigen::MatrixXi T = split_into_tets(hex).T;
  const ParamLocator locator(hex.V, T);  // identity "parameterization"
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> d(0, 1);
  int hint = -1;
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector3d q(d(rng), d(rng), d(rng));
    const auto hit = locator.locate(q, hint);
    hint = hit.tet;
    ASSERT_GE(hit.tet, 0);
    EXPECT_EQ(hit.violation, 0.0);
    EXPECT_GE(hit.bary.minCoeff(), -1e-12);
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) x += hit.bary(k) * hex.V.row(T(hit.tet, k)).transpose();
    EXPECT_LT((x - q).norm(), 1e-12);
  }
  EXPECT_GT(locator.walk_hits(), 0);
}

TEST(ParamLocator, PointsOutsideGetTheNearestTet) {
  const VolumeMesh hex = test::hex_box(2, 2, 2);
  const Eigen::MatrixXi T = split_into_tets(hex).T;
  const ParamLocator locator(hex.V, T);
  const auto hit = locator.locate(Eigen::Vector3d(1.01, 0.5, 0.5));
  ASSERT_GE(hit.tet, 0);
  EXPECT_GT(hit.violation, 0);
  EXPECT_LT(hit.violation, 0.1);
}

// A point in a hole of the image (where a fold leaves no tet, or an opening of the model) gets the tet that violates
// least, as a search over every tet finds it; also when queried again, and after another locator's queries.
TEST(ParamLocator, APointInAHoleGetsTheLeastViolatingTet) {
  const VolumeMesh hex = test::hex_box(6, 6, 6);
  const Eigen::MatrixXi all = split_into_tets(hex).T;
  std::vector<int> kept;
  for (int t = 0; t < all.rows(); ++t) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) centroid += hex.V.row(all(t, k)).transpose() / 4;
    if ((centroid.array() - 0.5).abs().maxCoeff() > 1.0 / 6) kept.push_back(t);  // a hole of 2 x 2 x 2 cells
  }
  Eigen::MatrixXi T(kept.size(), 4);
  for (size_t i = 0; i < kept.size(); ++i) T.row(i) = all.row(kept[i]);
  const ParamLocator holed(hex.V, T), whole(hex.V, all);
  const auto least_violation = [&](const Eigen::Vector3d& q) {
    double least = std::numeric_limits<double>::infinity();
    for (int t = 0; t < T.rows(); ++t) {
      Eigen::Matrix3d D;
      for (int k = 0; k < 3; ++k) D.col(k) = (hex.V.row(T(t, k + 1)) - hex.V.row(T(t, 0))).transpose();
      const Eigen::Vector3d l = D.inverse() * (q - hex.V.row(T(t, 0)).transpose());
      least = std::min(least, std::max(0.0, -std::min(1 - l.sum(), l.minCoeff())));
    }
    return least;
  };
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> in_hole(0.5 - 0.15, 0.5 + 0.15);
  for (int i = 0; i < 20; ++i) {
    const Eigen::Vector3d q(in_hole(rng), in_hole(rng), in_hole(rng));
    const double expected = least_violation(q);
    ASSERT_GT(expected, 0);
    for (int again = 0; again < 2; ++again) {
      const ParamLocator::Hit hit = holed.locate(q, 0);
      ASSERT_GE(hit.tet, 0);
      EXPECT_NEAR(hit.violation, expected, 1e-12) << i;
      EXPECT_EQ(whole.locate(q).violation, 0.0);
    }
  }
}

TransferOptions default_options() { return TransferOptions{}; }

// The standard mapped onto its own auxiliary tet model is the identity.
TEST(HexTransfer, StandardOntoItselfIsTheIdentity) {
  VolumeMesh standard = test::hex_box(5, 3, 4, 50, 12, 40);
  test::jitter_interior(standard, 1.0);
  const VolumeMesh patient = VolumeMesh::from_tets(standard.V, split_into_tets(standard).T);
  VolumeMesh patient_with_mask = patient;
  patient_with_mask.point_data = standard.point_data;
  const TransferRun run = run_transfer(standard, auxiliary_domain(standard), side_constraints(), "standard",
                                       patient_with_mask, side_constraints(), "patient", default_options());
  EXPECT_TRUE(run.patient.health.ok());
  EXPECT_LT((run.patient_hex.V - standard.V).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_EQ(run.patient_hex.C, standard.C);
  EXPECT_EQ(run.transfer.located_nearest, 0);
}

// A box mapped onto an affinely stretched box: harmonic fields of an affine image are the affine images of the
// fields, so the map is the affine map itself (and boundary vertices land exactly on the target's faces).
TEST(HexTransfer, BoxOntoStretchedBoxIsTheAffineMap) {
  const VolumeMesh standard = test::hex_box(4, 3, 5, 40, 10, 50);
  VolumeMesh target_hex = test::hex_box(8, 5, 9, 40, 10, 50);
  const Eigen::Vector3d scale(1.3, 0.7, 1.1);
  target_hex.V = target_hex.V * scale.asDiagonal();
  VolumeMesh patient = VolumeMesh::from_tets(target_hex.V, split_into_tets(target_hex).T);
  patient.point_data = target_hex.point_data;
  const TransferRun run = run_transfer(standard, auxiliary_domain(standard), side_constraints(), "standard", patient,
                                       side_constraints(), "patient", default_options());
  const Eigen::MatrixXd expected = standard.V * scale.asDiagonal();
  EXPECT_LT((run.patient_hex.V - expected).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_EQ(run.transfer.snap_failures, 0);
  // Boundary vertices exactly on the target's faces.
  for (int v = 0; v < standard.V.rows(); ++v)
    for (int d = 0; d < 3; ++d)
      if (standard.V(v, d) == 0.0) {
        EXPECT_EQ(run.patient_hex.V(v, d), 0.0);
      }
}

// The run's progress rises from 0 to 1 through the parameterization, the mapping, the shape relaxation (per sweep) and
// the repair, and a cancel during the relaxation stops the run.
TEST(HexTransfer, ReportsEveryStageInOrderAndCancelsInTheRelaxation) {
  VolumeMesh standard = test::hex_box(4, 3, 5, 40, 10, 50);
  VolumeMesh target_hex = test::hex_box(8, 5, 9, 40, 10, 50);
  target_hex.V.col(1) += 0.002 * target_hex.V.col(0).cwiseProduct(target_hex.V.col(0));  // bent: not affine
  VolumeMesh patient = VolumeMesh::from_tets(target_hex.V, split_into_tets(target_hex).T);
  patient.point_data = target_hex.point_data;
  std::vector<std::pair<std::string, double>> reports;
  const ProgressCallback record = [&](const std::string& stage, double f) {
    reports.emplace_back(stage, f);
    return true;
  };
  const TransferRun run = run_transfer(standard, auxiliary_domain(standard), side_constraints(), "standard", patient,
                                       side_constraints(), "patient", default_options(), record);
  ASSERT_FALSE(reports.empty());
  for (size_t i = 1; i < reports.size(); ++i)
    EXPECT_GE(reports[i].second, reports[i - 1].second) << reports[i].first << " after " << reports[i - 1].first;
  EXPECT_DOUBLE_EQ(reports.back().second, 1.0);
  auto first_of = [&](const std::string& stage) {
    return std::find_if(reports.begin(), reports.end(), [&](const auto& r) { return r.first == stage; });
  };
  const auto mapping = first_of("mapping vertices"), relaxation = first_of("shape relaxation"),
             repair = first_of("repairing folded cells");
  ASSERT_NE(relaxation, reports.end());
  ASSERT_NE(repair, reports.end());
  EXPECT_LT(mapping, relaxation);
  EXPECT_LT(relaxation, repair);
  EXPECT_EQ(std::count_if(reports.begin(), reports.end(), [](const auto& r) { return r.first == "shape relaxation"; }),
            run.relaxation.sweeps);  // one per sweep

  const ProgressCallback cancel_in_relaxation = [](const std::string& stage, double) {
    return stage != "shape relaxation";
  };
  EXPECT_THROW(run_transfer(standard, auxiliary_domain(standard), side_constraints(), "standard", patient,
                            side_constraints(), "patient", default_options(), cancel_in_relaxation),
               Cancelled);
}

}  // namespace
}  // namespace facehex

namespace facehex {
namespace {

// The same input gives bit-identical fields (small systems are factored concurrently, one per thread: with the
// shared elimination order, which thread factors which field does not change a bit).
TEST(HarmonicFieldsDeterminism, TwoRunsAreBitIdentical) {
  VolumeMesh hex = test::hex_box(12, 6, 10, 60, 15, 50);
  test::jitter_interior(hex, 0.8);
  const TetDomain domain = auxiliary_domain(hex);
  const ModelParameterization a =
      parameterize_model(domain.V, domain.T, domain.side_mask, side_constraints(), "box", HarmonicFieldsOptions{});
  const ModelParameterization b =
      parameterize_model(domain.V, domain.T, domain.side_mask, side_constraints(), "box", HarmonicFieldsOptions{});
  EXPECT_EQ(a.fields.uvw, b.fields.uvw);
}

// A field whose factorization fails (here: no Dirichlet condition) is reported by name, also when the three fields
// are factored concurrently.
TEST(HarmonicFieldsDeterminism, AFailedFactorizationIsReportedByItsField) {
  const VolumeMesh hex = test::hex_box(6, 4, 5, 60, 15, 50);
  const TetDomain domain = auxiliary_domain(hex);
  ResolvedConstraints constraints =
      resolve_constraints(side_constraints(), domain.V, domain.T, domain.side_mask, "box");
  constraints.fields[1] = DirichletConditions{};
  try {
    const HarmonicFields fields(domain.V, domain.T, constraints, HarmonicFieldsOptions{});
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("v: no Dirichlet condition"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace facehex
