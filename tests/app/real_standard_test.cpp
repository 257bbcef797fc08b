// Integration tests on the real standard mesh (../shared; skipped when absent) and the bundled resources.
#include "core/constraint_set.h"
#include "core/hex_to_tets.h"
#include "core/io/mesh_io.h"
#include "core/quality/hex_quality.h"
#include "core/resources.h"
#include "core/shell_sides.h"
#include "core/transfer_pipeline.h"

#include <gtest/gtest.h>

#include <cstdio>
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

// Mapping the standard onto its own tet model: where its parameterization is a bijection the map is the identity;
// near the few folds around its openings a vertex can be found in an overlapping tet.
TEST(BundledStandard, MapsOntoItsOwnTetModelAsTheIdentityAwayFromFolds) {
  const BundledModel standard = default_standard();
  const VolumeMesh hex = read_volume_mesh(standard.mesh);
  const ConstraintSet set = read_constraint_set(standard.constraints);
  const StandardDomain domain = auxiliary_domain(hex);
  VolumeMesh patient = VolumeMesh::from_tets(domain.V, domain.T);
  patient.point_data = hex.point_data;
  TransferOptions options;
  options.allow_inverted_parameterization = true;  // the standard's own folds (reported in its health)
  options.untangle = false;
  const TransferRun run = run_transfer(hex, domain, set, standard.constraints, patient, set, "self", options);
  int exact = 0;
  for (int v = 0; v < hex.num_vertices(); ++v) exact += (run.patient_hex.V.row(v) - hex.V.row(v)).norm() < 1e-6;
  std::printf("identity within 1e-6 mm at %d of %d vertices\n", exact, hex.num_vertices());
  EXPECT_GT(exact, 0.97 * hex.num_vertices());
}

}  // namespace
}  // namespace facehex
