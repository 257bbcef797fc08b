// Integration tests on the real standard mesh (../shared; skipped when absent) and the bundled resources.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "core/constraint_set.h"
#include "core/corner_jacobian.h"
#include "core/hex_to_tets.h"
#include "core/io/mesh_io.h"
#include "core/quality/hex_quality.h"
#include "core/resources.h"
#include "core/shell_sides.h"
#include "core/standard/closed_domain.h"
#include "core/transfer_pipeline.h"

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
  patient.point_data[kSideMaskArray] = domain.side_mask.cast<double>();  // the labels the standard is solved with
  TransferOptions options;
  options.allow_inverted_parameterization = true;  // the standard's own folds (reported in its health)
  options.untangle = false;
  const TransferRun run = run_transfer(hex, domain, set, standard.constraints, patient, set, "self", options);
  int exact = 0;
  for (int v = 0; v < hex.num_vertices(); ++v) exact += (run.patient_hex.V.row(v) - hex.V.row(v)).norm() < 1e-6;
  std::printf("identity within 1e-6 mm at %d of %d vertices\n", exact, hex.num_vertices());
  EXPECT_GT(exact, 0.97 * hex.num_vertices());
}

// The standard's hex vertices placed at their own (u, v, w): a feature slab that pins two rows of vertices to one value
// flattens the cells between them in parameter space, hence in every patient (the 2 mm slab flattened 72 cells of
// the nose). The only flat cells left are the four at the lower corners of the two lateral ends, where faces turn
// the corner; there the side labels of a middle vertex are relaxed, so the repair can lift it off the edge.
TEST(BundledStandard, OnlyRelaxedCornerCellsAreFlatInItsOwnParameterization) {
  const BundledModel standard = default_standard();
  const VolumeMesh hex = read_volume_mesh(standard.mesh);
  const StandardDomain domain = closed_domain(hex);
  const ModelParameterization p =
      parameterize_model(domain.V, domain.T, domain.side_mask, read_constraint_set(standard.constraints),
                         standard.constraints, HarmonicFieldsOptions{});
  VolumeMesh in_parameter_space = hex;
  in_parameter_space.V = p.fields.uvw.topRows(hex.num_vertices());
  if (p.health.orientation < 0) in_parameter_space.V.col(0) = 1.0 - in_parameter_space.V.col(0).array();
  const CornerJacobianCheck check = check_corner_jacobians(in_parameter_space);
  const Eigen::VectorXi labelled = side_mask_of(hex);
  EXPECT_EQ(domain.relaxed_corner_vertices, 4);  // two at each lower corner of the two lateral ends
  int flat = 0;
  for (int c : check.unusable()) {
    if (std::abs(check.min_determinant(c)) > 1e-12) continue;  // folded near an opening, not flat
    ++flat;
    bool has_relaxed_vertex = false;
    for (int i = 0; i < node_count(hex.types[c]); ++i)
      has_relaxed_vertex |= domain.side_mask(hex.C(c, i)) != labelled(hex.C(c, i));
    EXPECT_TRUE(has_relaxed_vertex) << "cell " << c << " is flat in parameter space";
  }
  EXPECT_LE(flat, 4);
}

}  // namespace
}  // namespace facehex
