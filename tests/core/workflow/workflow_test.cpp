// The workflow both front ends call: the constraint policy, the domains, the standard's checks, the exit policy.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/face/automatic_constraints.h"
#include "core/io/mesh_io.h"
#include "core/mesh/ct_landmarks.h"
#include "core/mesh/hex_to_tets.h"
#include "core/mesh/sides.h"
#include "core/standard/closed_domain.h"
#include "core/util/error.h"
#include "core/workflow/patient_setup.h"
#include "core/workflow/standard_setup.h"
#include "core/workflow/transfer.h"
#include "tests/core/test_meshes.h"

namespace facehex {
namespace {
namespace fs = std::filesystem;

// A box of tets with the six sides labelled (the hex box's side_mask), which has no face to find landmarks on.
VolumeMesh tet_box() {
  const VolumeMesh hex = test::hex_box(3, 2, 3, 30, 10, 30);
  VolumeMesh tets = VolumeMesh::from_tets(hex.V, split_into_tets(hex).T);
  tets.point_data = hex.point_data;
  return tets;
}

class Workflow : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("facehex-workflow-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST_F(Workflow, AGivenConstraintFileWinsOverOneBesideTheModel) {
  write_volume_mesh(path("box.vtu"), tet_box());
  ConstraintSet beside = side_constraints();
  beside.constraints.pop_back();
  write_constraint_set(path("box.json"), beside);
  ConstraintSet given = side_constraints();
  given.constraints.resize(2);
  write_constraint_set(path("given.json"), given);

  const PatientSetup from_given = load_patient(path("box.vtu"), {}, path("given.json"), nullptr);
  EXPECT_EQ(from_given.constraints.constraints.size(), 2u);
  EXPECT_EQ(from_given.constraints_path, path("given.json"));
  EXPECT_EQ(from_given.source(), path("given.json"));

  const PatientSetup from_beside = load_patient(path("box.vtu"), {}, "", nullptr);
  EXPECT_EQ(from_beside.constraints.constraints.size(), side_constraints().constraints.size() - 1);
  EXPECT_EQ(from_beside.constraints_path, path("box.json"));
}

TEST_F(Workflow, ConstraintsJsonInTheFolderIsTheBundledLayout) {
  write_volume_mesh(path("patient.vtu"), tet_box());
  ConstraintSet set = side_constraints();
  set.constraints.resize(3);
  write_constraint_set(path("constraints.json"), set);
  const PatientSetup p = load_patient(path("patient.vtu"), {}, "", nullptr);
  EXPECT_EQ(p.constraints.constraints.size(), 3u);
  EXPECT_EQ(p.constraints_path, path("constraints.json"));
}

TEST_F(Workflow, WithoutAFileAModelWithSidesGetsItsSidesAndSaysWhyNoFeatures) {
  write_volume_mesh(path("box.vtu"), tet_box());
  const PatientSetup no_values = load_patient(path("box.vtu"), {}, "", nullptr);
  EXPECT_EQ(no_values.constraints.constraints.size(), side_constraints().constraints.size());
  EXPECT_TRUE(no_values.constraints_path.empty());
  EXPECT_FALSE(no_values.features_problem.empty());
  EXPECT_FALSE(no_values.landmarks.has_value());

  // A box has no face: the landmarks are not found, the sides stay, and the problem is the finder's message.
  std::map<std::string, double> values;
  for (const auto& spec : feature_specs()) values[spec.name] = 0.5;
  const PatientSetup box = load_patient(path("box.vtu"), {}, "", &values);
  EXPECT_EQ(box.constraints.constraints.size(), side_constraints().constraints.size());
  EXPECT_FALSE(box.features_problem.empty());
  EXPECT_NE(box.constraints_note.find(box.features_problem), std::string::npos);
}

// Without side labels nothing can be placed: the model opens with no constraints (the application's user places them
// with the plane) and features_problem says why (the command line stops on it).
TEST_F(Workflow, AModelWithoutSidesOrConstraintFileGetsNoConstraintsAndTheReason) {
  VolumeMesh box = tet_box();
  box.point_data.clear();
  write_volume_mesh(path("bare.vtu"), box);
  std::map<std::string, double> values;
  for (const auto& spec : feature_specs()) values[spec.name] = 0.5;
  const PatientSetup p = load_patient(path("bare.vtu"), {}, "", &values);
  EXPECT_TRUE(p.constraints.constraints.empty());
  EXPECT_TRUE(p.constraints_path.empty());
  EXPECT_NE(p.features_problem.find("side_mask"), std::string::npos) << p.features_problem;
  EXPECT_NE(p.constraints_note.find("no constraints"), std::string::npos) << p.constraints_note;
}

TEST_F(Workflow, ATetModelIsItsOwnDomainWithAllItsVerticesAsModelVertices) {
  const VolumeMesh box = tet_box();
  const TetDomain d = own_domain(box);
  EXPECT_EQ(d.hex_vertices, box.num_vertices());
  EXPECT_EQ(d.V, box.V);
  EXPECT_EQ(d.T, box.tets());
  EXPECT_EQ(d.side_mask.size(), box.num_vertices());
  const PatientSetup p = patient_from_mesh(box, "in memory", nullptr);
  EXPECT_EQ(p.domain.hex_vertices, box.num_vertices());
  EXPECT_TRUE(p.constraints_path.empty());
}

// A model whose openings were closed by plugs (close_openings) is written with its own point data, the plugs' inner
// vertices on no side.
TEST_F(Workflow, TheParameterizedModelKeepsTheModelsPointDataWithItsPlugs) {
  // A tunnel from back to front through the middle column of the box.
  VolumeMesh model = test::tet_box_without(3, 2, 3, 30, 10, 30, [](int i, int, int k) { return i == 1 && k == 1; });
  CtLandmarks found;
  found.stomion = CtLandmark{Eigen::Vector3d(15, 10, 12), false};
  set_ct_landmarks(model, found);
  const TetDomain closed = close_openings(own_domain(model), "the model's own tets");
  ASSERT_EQ(closed.closed_openings, 1);
  const ModelParameterization p =
      parameterize_model(closed.V, closed.T, closed.side_mask, side_constraints(), "box", HarmonicFieldsOptions{});
  const VolumeMesh written = parameterized_tet_mesh(p, &model);
  ASSERT_EQ(written.point_data.count(kSideMaskArray), 1u);
  const Eigen::MatrixXd& mask = written.point_data.at(kSideMaskArray);
  ASSERT_EQ(mask.rows(), closed.V.rows());
  EXPECT_EQ(mask.topRows(model.num_vertices()), model.point_data.at(kSideMaskArray));
  EXPECT_TRUE(mask.bottomRows(closed.V.rows() - model.num_vertices()).isZero());
  // The landmarks read in the CT go with the model, so that running the written model finds them again.
  const std::optional<CtLandmarks> kept = ct_landmarks(written, "written");
  ASSERT_TRUE(kept.has_value());
  ASSERT_TRUE(kept->stomion.has_value());
  EXPECT_EQ(kept->stomion->point, found.stomion->point);
  // A model of other vertices lends none.
  VolumeMesh other = model;
  other.V.array() += 1;
  EXPECT_EQ(parameterized_tet_mesh(p, &other).point_data.count(kSideMaskArray), 0u);
  EXPECT_TRUE(parameterized_tet_mesh(p, &other).field_data.empty());
}

TEST_F(Workflow, AStandardMustBeHexDominantAndItsDomainKindKnown) {
  write_volume_mesh(path("tets.vtu"), tet_box());
  write_constraint_set(path("tets.json"), side_constraints());
  EXPECT_THROW(load_standard(path("tets.vtu")), Error);
  const VolumeMesh hex = test::hex_box(3, 2, 3, 30, 10, 30);
  EXPECT_THROW(standard_domain(hex, "open"), Error);
  EXPECT_NO_THROW(check_standard_domain_kind("closed"));
  EXPECT_NO_THROW(check_standard_domain_kind("auxiliary"));
  EXPECT_THROW(check_standard_domain_kind("open"), Error);
  const TetDomain aux = standard_domain(hex, "auxiliary");
  EXPECT_EQ(aux.hex_vertices, hex.num_vertices());
}

TEST(ExitCode, ZeroOnlyWhenNoCellIsInvertedOrFlat) {
  QualitySummary q;
  q.cells = 10;
  EXPECT_EQ(exit_code(q), 0);
  q.inverted = 1;
  EXPECT_EQ(exit_code(q), kExitUnusableCells);
  q.inverted = 0;
  q.degenerate = 2;
  EXPECT_EQ(exit_code(q), kExitUnusableCells);
  EXPECT_EQ(kExitUnusableCells, 3);
}

}  // namespace
}  // namespace facehex
