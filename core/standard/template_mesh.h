#pragma once
// A new standard hex mesh from a reference soft-tissue tet model (the paper's template tools, section 3.1).
//
// The paper builds its standard by hand from plane sections: vertical and horizontal curves on the outer surface,
// rows aligned with the feature lines, the grid pushed to the inner surface and intermediate layers interpolated.
// Here the reference's own harmonic parameterization plays the part of the plane sections. The template is a
// structured grid in the unit cube (u across the face, v from the chin to the forehead, w from the bone to the skin):
//  - its u and v lines include every feature value, so whole rows of vertices lie on the mid-sagittal, eyebrow,
//    below-nose and middle lip features;
//  - between those values, lines are equally spaced in arc length along the reference, so that cells are about
//    cell_size long along the face;
//  - its w lines split the tissue into `layers` layers of equal parametric thickness.
// The grid is then mapped onto the reference by the transfer every standard goes through (transfer_pipeline.h), which
// puts the outer rows on the skin and the inner rows on the bone; its vertices then slide along the reference towards
// ideal cells (the shape relaxation, with the ideal cell as target), and the repair improves every cell below its
// bound, cutting the reference's sharp corners where it must (TemplateOptions::cut_sharp_corners).
//
// Grid indexing: (i, j, k) over (u, v, w), vertex id = (k * (nv + 1) + j) * (nu + 1) + i, where nu, nv, nw are the
// numbers of cells along each field.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "core/fields/constraint_set.h"
#include "core/mapping/hex_transfer.h"
#include "core/mapping/transfer_pipeline.h"
#include "core/mesh/mesh.h"

namespace facehex {

struct TemplateOptions {
  int layers = 3;          // hex layers from the bone (w0) to the skin (w1)
  double cell_size = 0;    // mm along the face; 0: the reference's mean soft-tissue thickness / layers (cube-like)
  int curve_samples = 96;  // points per curve when measuring arc lengths
  // After the mapping, every vertex slides along the reference (side and feature vertices on their side or feature)
  // towards ideal cells, which raises both the mean and the minimum cell shape. false: the grid as laid out (its
  // vertices exactly at their grid values), then the repair.
  bool relax = true;
  // Where the reference's sides meet at a sharp corner (a thin fin of tissue between a cut and the bone), the cells
  // there cannot reach the repair's bound with their side vertices on the sides: the last polish then moves those
  // vertices in space, so the template cuts the corner. false: every side vertex stays on the reference's surfaces.
  bool cut_sharp_corners = true;
};

struct TemplateGrid {
  std::array<std::vector<double>, 3> lines;  // ascending grid-line values of u, v, w in [0, 1], ends included
  double cell_size = 0;                      // mm, as used
  double mean_thickness = 0;                 // mm, reference's mean bone-to-skin distance along w
  int cells(int field) const { return static_cast<int>(lines[field].size()) - 1; }
};

// Grid lines for the reference model (its inverse parameterization) with feature values per field (values strictly
// inside (0, 1); u, v only). Throws facehex::Error("template", ...) for bad options or feature values.
TemplateGrid template_grid(const PatientMap& reference, const std::array<std::vector<double>, 3>& features,
                           const TemplateOptions& options);

// The grid as a hex mesh in parameter space, with "side_mask" point data. Its vertices sit at (u, v, w), or at
// (u, w, v) when mirrored, so that its parameterization has the handedness of a model whose (u, v, w) frame is
// left-handed (ParamHealth::orientation -1); hexes are positively oriented in that embedding.
VolumeMesh grid_hex_mesh(const TemplateGrid& grid, bool mirrored);

// The template's constraint set: the six sides, and each feature constraint of `reference_set` (a constraint that
// selects no side) as the grid row at its value, by vertex ids. V: the template's vertex positions on the reference,
// to restrict each row as the reference's selection is (its region, within-sphere and excluded sides; the plane and
// band are replaced by the row); empty: whole rows. Throws if a feature value is not a grid line.
ConstraintSet grid_constraints(const TemplateGrid& grid, const ConstraintSet& reference_set,
                               const Eigen::MatrixXd& V = Eigen::MatrixXd());

// The feature values of a constraint set per field (its constraints that select no side).
std::array<std::vector<double>, 3> feature_lines(const ConstraintSet& set);

struct TemplateResult {
  VolumeMesh mesh;            // the new standard (hexes, "side_mask" point data)
  ConstraintSet constraints;  // its constraint set (grid_constraints on its positions)
  TemplateGrid grid;
  TransferRun run;  // the reference's parameterization, the mapping and the repair (reports)
};

// The whole construction: parameterize the reference (V, T, side_mask) with its constraint set, lay out the grid,
// map it onto the reference and repair it with `transfer` (cells below transfer.untangle_options.min_scaled_jacobian
// are improved too). source names the reference in errors.
TemplateResult build_template(const VolumeMesh& reference, const ConstraintSet& reference_set,
                              const std::string& source, const TemplateOptions& options,
                              const TransferOptions& transfer, const ProgressCallback& progress = {});

}  // namespace facehex
