// Integration tests on the real standard mesh and the other bundled resources.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>

#include "core/face/automatic_constraints.h"
#include "core/fields/constraint_set.h"
#include "core/io/mesh_io.h"
#include "core/mapping/transfer_pipeline.h"
#include "core/mesh/corner_jacobian.h"
#include "core/mesh/hex_to_tets.h"
#include "core/mesh/shell_sides.h"
#include "core/quality/hex_quality.h"
#include "core/standard/closed_domain.h"
#include "core/standard/parameterization_cache.h"
#include "core/util/resources.h"

namespace facehex {
namespace {

TEST(RealStandard, SidesOfTheArtisynthFaceAreFoundFromItsStructure) {
  // The bundled copy of the ArtiSynth face (its ANSYS files converted: the same nodes and cells).
  const VolumeMesh m = read_volume_mesh(find_standard("artisynth-refface").mesh);
  const ShellSides sides = label_shell_sides(m, default_shell_frame(m.V));
  // Outer and inner sides pair up face for face through the element layers.
  EXPECT_EQ(sides.faces_per_side[W0], sides.faces_per_side[W1]);
  EXPECT_GT(sides.faces_per_side[W1], 2000);
  // The two lateral ends mirror each other (the mesh is symmetric in x).
  EXPECT_EQ(sides.faces_per_side[U0], sides.faces_per_side[U1]);
  for (int s = 0; s < kNumSides; ++s) EXPECT_GT(sides.faces_per_side[s], 20) << kSideNames[s];
  EXPECT_GT(sides.opening_faces, 0);  // eyes, nostrils and mouth are openings, left free
  EXPECT_EQ(sides.conflicting_vertices, 0);
  // The bundled labels are the labeller's (the walls between the nostrils left free, not skin and bone).
  EXPECT_TRUE(sides.side_mask == side_mask_of(m)) << "relabel with: facehex sides standard.vtu -o standard.vtu";
}

// Mapping the standard onto its own tet model: where its parameterization is a bijection the map is the identity;
// near the few folds around its openings a vertex can be found in an overlapping tet.
TEST(BundledStandard, MapsOntoItsOwnTetModelAsTheIdentityAwayFromFolds) {
  const BundledModel standard = default_standard();
  const VolumeMesh hex = read_volume_mesh(standard.mesh);
  const ConstraintSet set = read_constraint_set(standard.constraints);
  const TetDomain domain = auxiliary_domain(hex);
  VolumeMesh patient = VolumeMesh::from_tets(domain.V, domain.T);
  patient.point_data[kSideMaskArray] = domain.side_mask.cast<double>();  // the labels the standard is solved with
  TransferOptions options;
  options.allow_inverted_parameterization = true;  // the standard's own folds (reported in its health)
  options.repair_folds = false;
  const TransferRun run = run_transfer(hex, domain, set, standard.constraints, patient, set, "self", options);
  int exact = 0;
  for (int v = 0; v < hex.num_vertices(); ++v) exact += (run.mapped_hex.V.row(v) - hex.V.row(v)).norm() < 1e-6;
  std::printf("mapping: identity within 1e-6 mm at %d of %d vertices\n", exact, hex.num_vertices());
  EXPECT_GT(exact, 0.97 * hex.num_vertices());
  // The shape relaxation opens the folds and moves their neighbourhood a little; the rest stays in place.
  std::vector<double> moved(hex.num_vertices());
  for (int v = 0; v < hex.num_vertices(); ++v) moved[v] = (run.patient_hex.V.row(v) - hex.V.row(v)).norm();
  std::sort(moved.begin(), moved.end());
  std::printf("relaxed: moved p50 %.2g, p90 %.2g, p97 %.2g, max %.2g mm\n", moved[moved.size() / 2],
              moved[moved.size() * 9 / 10], moved[moved.size() * 97 / 100], moved.back());
  EXPECT_LT(moved[moved.size() / 2], 0.1);
}

// The standard's hex vertices placed at their own (u, v, w): a feature slab that pins two rows of vertices to one value
// flattens the cells between them in parameter space, hence in every patient (the 2 mm slab flattened 72 cells of
// the nose). The only flat cells left are the four at the lower corners of the two lateral ends, where faces turn
// the corner; there the side labels of a middle vertex are relaxed, so the repair can lift it off the edge.
TEST(BundledStandard, OnlyRelaxedCornerCellsAreFlatInItsOwnParameterization) {
  const BundledModel standard = default_standard();
  const VolumeMesh hex = read_volume_mesh(standard.mesh);
  const TetDomain domain = closed_domain(hex);
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

// The shipped parameterization caches fit their standards as bundled (closed domain, default field options): a
// standard or constraint set edited without `facehex standards --write-cache` fails here, not silently at run time.
TEST(BundledStandard, ParameterizationCachesAreFreshAndGiveTheComputedFields) {
  for (const BundledModel& standard : bundled_standards()) {
    const VolumeMesh hex = read_volume_mesh(standard.mesh);
    const ConstraintSet set = read_constraint_set(standard.constraints);
    const TetDomain domain = closed_domain(hex);
    std::string why;
    const auto cached = read_parameterization_cache(parameterization_cache_path(standard.mesh), domain, set, {}, &why);
    ASSERT_TRUE(cached) << standard.name << ": " << why;
    const ModelParameterization computed =
        parameterize_model(domain.V, domain.T, domain.side_mask, set, standard.constraints, {});
    EXPECT_LT((cached->fields.uvw - computed.fields.uvw).cwiseAbs().maxCoeff(), 1e-12) << standard.name;
    EXPECT_EQ(cached->health.inverted, computed.health.inverted) << standard.name;
  }
}

// The second bundled standard, made by `facehex template` from the bundled CT (resources/standards/headsq-template):
// the quality bounds where they are met, its constraint set, and feature values shared with the first
// standard, so that patients' features correspond whichever standard is picked.
TEST(BundledTemplate, IsValidWithTheFeaturesOfTheFirstStandard) {
  const BundledModel standard = find_standard("headsq-template");
  const VolumeMesh hex = read_volume_mesh(standard.mesh);
  EXPECT_EQ(hex.count(CellType::Hex), hex.num_cells());
  const QualitySummary q = summarize(hex, element_quality(hex));
  EXPECT_EQ(q.inverted, 0);
  EXPECT_EQ(q.degenerate, 0);
  EXPECT_GE(q.shape_mean, 0.75);
  EXPECT_GE(q.scaled_jacobian_min, 0.3);
  const ConstraintSet set = read_constraint_set(standard.constraints);
  const auto values = [](const ConstraintSet& s) {
    std::map<std::string, double> v;
    for (const Constraint& c : s.constraints)
      if (!c.select.side) v[c.name] = c.value;
    return v;
  };
  EXPECT_EQ(set.constraints.size(), 10u);
  EXPECT_EQ(values(set), values(read_constraint_set(default_standard().constraints)));
  for (const Constraint& c : set.constraints)
    for (int v : c.select.ids) ASSERT_LT(v, hex.num_vertices()) << c.name;

  // Mapped onto the bundled patient (the model it was built from, with the automatic constraints): no inverted or flat
  // cell after the repair, and the angles nearly kept (the map is close to the identity).
  const BundledModel patient_files = default_patient();
  const VolumeMesh patient = read_volume_mesh(patient_files.mesh);
  const ConstraintSet patient_set = automatic_constraints(
      patient.V, side_mask_of(patient), landmark_options_for(patient, patient_files.mesh), feature_values(set));
  const TransferRun run = run_transfer(hex, closed_domain(hex), set, standard.constraints, patient, patient_set,
                                       patient_files.mesh, TransferOptions{});
  // Its own parameterization folds at a handful of tets (the bone under the nose, the chin's lower edge), as the
  // hand-built standard's does around its openings.
  EXPECT_LT(run.standard.health.inverted, 0.001 * run.standard.health.tets);
  const QualitySummary mapped = summarize(run.patient_hex, element_quality(run.patient_hex));
  EXPECT_EQ(mapped.inverted, 0);
  EXPECT_EQ(mapped.degenerate, 0);
  EXPECT_GE(mapped.shape_mean, 0.75);
  EXPECT_LT(dihedral_distortion(hex, run.patient_hex).mean_deg, 5.0);
}

}  // namespace
}  // namespace facehex
