#include "core/standard/template_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/mesh/corner_jacobian.h"
#include "core/mesh/hex_to_tets.h"
#include "core/util/error.h"
#include "tests/core/test_meshes.h"

namespace facehex {
namespace {

constexpr double kWidth = 40, kDepth = 10, kHeight = 30;  // mm: x (u), y (w), z (v) of the reference box

// The reference: a 40 x 10 x 30 mm box of tets, sides as test::hex_box labels them. Its harmonic fields are linear:
// u = x / 40, v = z / 30, w = y / 10 (a left-handed (u, v, w) frame).
VolumeMesh reference_box() {
  const VolumeMesh hex = test::hex_box(8, 3, 10, kWidth, kDepth, kHeight);
  VolumeMesh tets = VolumeMesh::from_tets(hex.V, split_into_tets(hex).T);
  tets.point_data = hex.point_data;
  return tets;
}

// Sides, a mid-sagittal plane (u = 0.5, whole volume) and a short line at z = 9 mm (v = 0.3) on the boundary within
// 12 mm of (20, 10, 9).
ConstraintSet reference_constraints() {
  ConstraintSet set = side_constraints();
  Constraint mid{"mid-sagittal line", 0, 0.5, {}, ""};
  mid.select.plane = PlaneSelection{};
  mid.select.plane->point = Eigen::Vector3d(kWidth / 2, 0, 0);
  mid.select.plane->normal = Eigen::Vector3d::UnitX();
  set.constraints.push_back(mid);
  Constraint nose{"below-nose line", 1, 0.3, {}, ""};
  nose.select.plane = PlaneSelection{};
  nose.select.plane->point = Eigen::Vector3d(0, 0, 0.3 * kHeight);
  nose.select.plane->normal = Eigen::Vector3d::UnitZ();
  nose.select.plane->region = "boundary";
  nose.select.plane->within_center = Eigen::Vector3d(kWidth / 2, kDepth, 0.3 * kHeight);
  nose.select.plane->within_radius = 12;
  set.constraints.push_back(nose);
  return set;
}

TemplateResult box_template(const TemplateOptions& options) {
  return build_template(reference_box(), reference_constraints(), "box", options, TransferOptions{});
}

// The grid as laid out, without the relaxation.
TemplateOptions layout_options() {
  TemplateOptions options;
  options.layers = 2;
  options.cell_size = 5;
  options.relax = false;
  return options;
}

// The reference box sheared so that its bottom (v0) meets its bone side (w0, y = 0) at 15 degrees: z += y cot 15.
const double kCot15 = 1 / std::tan(15 * std::acos(-1.0) / 180);
VolumeMesh sheared_box() {
  VolumeMesh sheared = reference_box();
  sheared.V.col(2) += kCot15 * sheared.V.col(1);
  return sheared;
}

// The largest distance of a side vertex of a template of the sheared box to the nearest of the box's six planes.
double sides_off_sheared_box(const VolumeMesh& hex) {
  const Eigen::MatrixXd& mask = hex.point_data.at(kSideMaskArray);
  const double s = std::sqrt(1 + kCot15 * kCot15);
  double worst = 0;
  for (int v = 0; v < hex.num_vertices(); ++v) {
    if (mask(v) == 0) continue;
    const Eigen::RowVector3d x = hex.V.row(v);
    const double d[6] = {
        x(0), kWidth - x(0), x(1), kDepth - x(1), (x(2) - kCot15 * x(1)) / s, (kHeight + kCot15 * x(1) - x(2)) / s};
    worst = std::max(worst, std::abs(*std::min_element(d, d + 6)));
  }
  return worst;
}

double mean_scaled_jacobian(const VolumeMesh& hex) {
  double sum = 0;
  for (int c = 0; c < hex.num_cells(); ++c) sum += scaled_jacobian(hex.types[c], cell_nodes(hex, c));
  return sum / hex.num_cells();
}

TEST(TemplateMesh, GridOnABoxIsTheLinearMapOfItsLines) {
  const TemplateResult t = box_template(layout_options());
  // Equal arc length = equal parameter steps on a box; the feature values are lines.
  EXPECT_EQ(t.grid.cells(0), 8);  // 40 mm / 5
  EXPECT_EQ(t.grid.cells(1), 6);  // 9 mm -> 2 cells, 21 mm -> 4 cells
  EXPECT_EQ(t.grid.cells(2), 2);
  EXPECT_NEAR(t.grid.mean_thickness, kDepth, 1e-9);
  for (int k = 0; k <= 8; ++k) EXPECT_NEAR(t.grid.lines[0][k], k / 8.0, 1e-9);
  EXPECT_NEAR(t.grid.lines[1][1], 0.15, 1e-9);
  EXPECT_NEAR(t.grid.lines[1][2], 0.3, 1e-12);
  EXPECT_NEAR(t.grid.lines[1][3], 0.3 + 0.7 / 4, 1e-9);

  // Every vertex sits where the linear parameterization puts its grid values: x = 40 u, y = 10 w, z = 30 v.
  const int nu = t.grid.cells(0), nv = t.grid.cells(1);
  ASSERT_EQ(t.mesh.num_cells(), 8 * 6 * 2);
  for (int v = 0; v < t.mesh.num_vertices(); ++v) {
    const int i = v % (nu + 1), j = (v / (nu + 1)) % (nv + 1), k = v / ((nu + 1) * (nv + 1));
    const Eigen::RowVector3d expected(kWidth * t.grid.lines[0][i], kDepth * t.grid.lines[2][k],
                                      kHeight * t.grid.lines[1][j]);
    EXPECT_LT((t.mesh.V.row(v) - expected).norm(), 1e-9) << "vertex " << v;
  }
  const CornerJacobianCheck check = check_corner_jacobians(t.mesh);
  EXPECT_TRUE(check.unusable().empty());
  EXPECT_GT(check.min_determinant.minCoeff(), 0.0);
  EXPECT_EQ(t.run.untangle.bad_before, 0);

  // Sides: vertices on u0 lie on x = 0, on w1 on y = 10.
  const Eigen::MatrixXd& mask = t.mesh.point_data.at(kSideMaskArray);
  for (int v = 0; v < t.mesh.num_vertices(); ++v) {
    const int bits = static_cast<int>(mask(v));
    if (bits & side_bit(U0)) {
      EXPECT_NEAR(t.mesh.V(v, 0), 0.0, 1e-12);
    }
    if (bits & side_bit(W1)) {
      EXPECT_NEAR(t.mesh.V(v, 1), kDepth, 1e-12);
    }
  }
}

TEST(TemplateMesh, FeatureRowsAreRestrictedAsTheReferenceSelection) {
  const TemplateResult t = box_template(layout_options());
  ASSERT_EQ(t.constraints.constraints.size(), 8u);  // six sides + two features
  const Constraint& mid = t.constraints.constraints[6];
  EXPECT_EQ(mid.name, "mid-sagittal line");
  EXPECT_EQ(mid.value, 0.5);
  EXPECT_EQ(mid.select.ids.size(), 7u * 3u);  // the whole row: (nv + 1) x (nw + 1)
  for (int v : mid.select.ids) EXPECT_NEAR(t.mesh.V(v, 0), kWidth / 2, 1e-9);
  const Constraint& nose = t.constraints.constraints[7];
  ASSERT_FALSE(nose.select.ids.empty());
  for (int v : nose.select.ids) {
    EXPECT_NEAR(t.mesh.V(v, 2), 0.3 * kHeight, 1e-9);
    EXPECT_LE((t.mesh.V.row(v) - Eigen::RowVector3d(kWidth / 2, kDepth, 0.3 * kHeight)).norm(), 12 + 1e-9);
  }
  // On the skin (y = 10): x in {10, ..., 30}; on the bone (y = 0): x in {15, 20, 25}; the middle layer is inside.
  EXPECT_EQ(nose.select.ids.size(), 8u);
}

// On the sheared box the harmonic parameterization is not linear, so the grid as laid out has uneven cells. The
// relaxation slides them towards ideal cells: the mean scaled Jacobian rises, every side vertex stays on its face of
// the box and the mid-sagittal row on its plane.
TEST(TemplateMesh, RelaxationEvensOutCellsAndKeepsSidesAndFeatures) {
  ConstraintSet set = reference_constraints();
  set.constraints.pop_back();  // the mid-sagittal plane only: x is not sheared
  TemplateOptions options = layout_options();
  options.cut_sharp_corners = false;
  const TemplateResult laid_out = build_template(sheared_box(), set, "sheared box", options, TransferOptions{});
  options.relax = true;
  const TemplateResult t = build_template(sheared_box(), set, "sheared box", options, TransferOptions{});
  EXPECT_GT(t.run.relaxation.sweeps, 0);
  EXPECT_GT(mean_scaled_jacobian(t.mesh), mean_scaled_jacobian(laid_out.mesh) + 0.01);
  EXPECT_TRUE(check_corner_jacobians(t.mesh).unusable().empty());
  EXPECT_LT(sides_off_sheared_box(t.mesh), 1e-6);
  ASSERT_EQ(t.constraints.constraints.size(), 7u);
  for (int v : t.constraints.constraints[6].select.ids) EXPECT_NEAR(t.mesh.V(v, 0), kWidth / 2, 1e-6);
}

// The sheared box's bottom meets its bone side at 15 degrees: the cells along that edge have the angle at a corner
// (scaled Jacobian about sin 15 deg = 0.26) as long as their side vertices stay on the two sides. By default the
// template cuts the corner and every cell reaches the bound; with cut_sharp_corners off, every side vertex stays on
// the reference's surface and the corner cells stay below it.
TEST(TemplateMesh, CutsASharpCornerOnlyWhenAllowed) {
  TransferOptions transfer;
  transfer.untangle_options.min_scaled_jacobian = 0.35;
  TemplateOptions options;
  options.layers = 2;
  options.cell_size = 5;
  TemplateOptions keep = options;
  keep.cut_sharp_corners = false;
  const TemplateResult kept = build_template(sheared_box(), side_constraints(), "sheared box", keep, transfer);
  EXPECT_LT(sides_off_sheared_box(kept.mesh), 1e-6);
  EXPECT_LT(kept.run.untangle.min_scaled_jacobian_after, 0.3);
  const TemplateResult cut = build_template(sheared_box(), side_constraints(), "sheared box", options, transfer);
  EXPECT_TRUE(check_corner_jacobians(cut.mesh).unusable().empty());
  EXPECT_GE(cut.run.untangle.min_scaled_jacobian_after, 0.3);
  EXPECT_GT(sides_off_sheared_box(cut.mesh), 0.1);  // the corner was cut
  EXPECT_LT(sides_off_sheared_box(cut.mesh), kDepth);
}

TEST(TemplateMesh, MirroredGridHexesArePositiveInTheirEmbedding) {
  TemplateGrid grid;
  grid.lines = {std::vector<double>{0, 0.5, 1}, std::vector<double>{0, 0.3, 1}, std::vector<double>{0, 1}};
  for (bool mirrored : {false, true}) {
    const VolumeMesh mesh = grid_hex_mesh(grid, mirrored);
    EXPECT_EQ(mesh.num_cells(), 4);
    EXPECT_TRUE(check_corner_jacobians(mesh).unusable().empty()) << "mirrored " << mirrored;
  }
}

TEST(TemplateMesh, RejectsBadOptionsAndFeatures) {
  TemplateOptions no_layers;
  no_layers.layers = 0;
  EXPECT_THROW(box_template(no_layers), Error);
  TemplateOptions negative;
  negative.cell_size = -1;
  EXPECT_THROW(box_template(negative), Error);
  ConstraintSet on_side = reference_constraints();
  on_side.constraints[6].value = 1.0;  // a feature at a shape end
  EXPECT_THROW(build_template(reference_box(), on_side, "box", TemplateOptions{}, TransferOptions{}), Error);
  ConstraintSet on_w = reference_constraints();
  on_w.constraints[7].field = 2;
  EXPECT_THROW(build_template(reference_box(), on_w, "box", TemplateOptions{}, TransferOptions{}), Error);
}

}  // namespace
}  // namespace facehex
