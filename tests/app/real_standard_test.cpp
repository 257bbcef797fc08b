// Integration tests on the real standard mesh (../shared; skipped when absent) and the bundled resources.
#include "core/constraint_set.h"
#include "core/hex_to_tets.h"
#include "core/io/mesh_io.h"
#include "core/quality/hex_quality.h"
#include "core/resources.h"
#include "core/shell_sides.h"
#include "core/transfer_pipeline.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace facehex {
namespace {

const std::string kRefFace = std::string(FACEHEX_SHARED_DIR) + "/data/standard/artisynth-refface/newface.elem";

TEST(RealStandard, SidesOfTheArtisynthFaceAreFoundFromItsStructure) {
  if (!std::filesystem::exists(kRefFace)) GTEST_SKIP() << "shared data not present";
  const VolumeMesh m = read_volume_mesh(kRefFace);
  const ShellSides sides = label_shell_sides(m, default_shell_frame(m.V));
  // Outer and inner sides pair up face for face through the element layers.
  EXPECT_EQ(sides.faces_per_side[W0], sides.faces_per_side[W1]);
  EXPECT_GT(sides.faces_per_side[W1], 2000);
  // The two lateral ends mirror each other (the mesh is symmetric in x).
  EXPECT_EQ(sides.faces_per_side[U0], sides.faces_per_side[U1]);
  for (int s = 0; s < kNumSides; ++s) EXPECT_GT(sides.faces_per_side[s], 20) << kSideNames[s];
  EXPECT_GT(sides.opening_faces, 0);  // eyes, nostrils and mouth are openings, left free
}

TEST(BundledStandard, MapsOntoItsOwnAuxiliaryTetModelAsTheIdentity) {
  const BundledModel standard = default_standard();
  const VolumeMesh hex = read_volume_mesh(standard.mesh);
  const ConstraintSet set = read_constraint_set(standard.constraints);
  VolumeMesh patient = VolumeMesh::from_tets(hex.V, split_into_tets(hex).T);
  patient.point_data = hex.point_data;
  const TransferRun run = run_transfer(hex, auxiliary_domain(hex), set, standard.constraints, patient, set, "self", TransferOptions{});
  EXPECT_LT((run.patient_hex.V - hex.V).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_EQ(summarize(run.patient_hex, element_quality(run.patient_hex)).inverted, 0);
}

}  // namespace
}  // namespace facehex
