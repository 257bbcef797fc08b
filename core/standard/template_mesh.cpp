#include "core/standard/template_mesh.h"

#include <algorithm>
#include <cmath>

#include "core/fields/tet_domain.h"
#include "core/mesh/sides.h"
#include "core/util/error.h"

namespace facehex {
namespace {

constexpr double kSameValue = 1e-9;

// Cumulative arc length through the reference along field f, the other coordinates as in q: s[k] at f = k / (n - 1).
std::vector<double> arc_length(const PatientMap& reference, int f, Eigen::Vector3d q, int n) {
  std::vector<double> s(n, 0.0);
  Eigen::Vector3d previous = Eigen::Vector3d::Zero();
  int hint = -1;
  for (int k = 0; k < n; ++k) {
    q(f) = static_cast<double>(k) / (n - 1);
    const PatientMap::Placement p = reference.place(q, hint);
    hint = p.tet;
    if (k > 0) s[k] = s[k - 1] + (p.x - previous).norm();
    previous = p.x;
  }
  return s;
}

// s at parameter t (s sampled at k / (n - 1)), and its inverse (s is non-decreasing).
double length_at(const std::vector<double>& s, double t) {
  const double x = t * static_cast<double>(s.size() - 1);
  const size_t k = std::min(static_cast<size_t>(x), s.size() - 2);
  return s[k] + (x - static_cast<double>(k)) * (s[k + 1] - s[k]);
}
double parameter_at(const std::vector<double>& s, double length) {
  const size_t k = std::clamp<size_t>(std::lower_bound(s.begin(), s.end(), length) - s.begin(), 1, s.size() - 1);
  const double span = s[k] - s[k - 1];
  const double within = span > 0 ? (length - s[k - 1]) / span : 0.0;
  return (static_cast<double>(k - 1) + within) / static_cast<double>(s.size() - 1);
}

int vertex_id(const TemplateGrid& grid, int i, int j, int k) {
  return (k * (grid.cells(1) + 1) + j) * (grid.cells(0) + 1) + i;
}

void check_options(const TemplateOptions& options) {
  if (options.layers < 1) throw Error("template", "the number of layers must be at least 1");
  if (options.cell_size < 0) throw Error("template", "the cell size must be positive (or 0 for automatic)");
  if (options.curve_samples < 8) throw Error("template", "at least 8 samples per curve are needed");
}

// The sides (sides.h bits) of the grid vertex with indices (i, j, k): the first and last line of each field.
int grid_side_mask(const TemplateGrid& grid, const std::array<int, 3>& index) {
  int mask = 0;
  for (int f = 0; f < 3; ++f) {
    if (index[f] == 0) mask |= side_bit(static_cast<Side>(2 * f));
    if (index[f] == grid.cells(f)) mask |= side_bit(static_cast<Side>(2 * f + 1));
  }
  return mask;
}

// Index of value in a field's lines, or -1.
int line_index(const std::vector<double>& lines, double value) {
  for (size_t i = 0; i < lines.size(); ++i)
    if (std::abs(lines[i] - value) <= kSameValue) return static_cast<int>(i);
  return -1;
}

}  // namespace

std::array<std::vector<double>, 3> feature_lines(const ConstraintSet& set) {
  std::array<std::vector<double>, 3> lines;
  for (const Constraint& c : set.constraints)
    if (!c.select.side) lines[c.field].push_back(c.value);
  return lines;
}

TemplateGrid template_grid(const PatientMap& reference, const std::array<std::vector<double>, 3>& features,
                           const TemplateOptions& options) {
  check_options(options);
  if (!features[2].empty()) throw Error("template", "feature constraints on w are not supported (layers are uniform)");
  TemplateGrid grid;
  // Mean bone-to-skin distance along w over the middle of the face.
  double thickness = 0;
  int count = 0;
  for (int a = 1; a <= 9; ++a)
    for (int b = 1; b <= 9; ++b) {
      const Eigen::Vector3d bone(a / 10.0, b / 10.0, 0.0), skin(a / 10.0, b / 10.0, 1.0);
      thickness += (reference.place(skin).x - reference.place(bone).x).norm();
      ++count;
    }
  grid.mean_thickness = thickness / count;
  grid.cell_size = options.cell_size > 0 ? options.cell_size : grid.mean_thickness / options.layers;

  for (int f = 0; f < 2; ++f) {
    // Mean arc length along f over curves across the face, on the bone and on the skin.
    const int g = 1 - f;
    std::vector<double> s(options.curve_samples, 0.0);
    int curves = 0;
    for (double across : {0.2, 0.5, 0.8})
      for (double depth : {0.0, 1.0}) {
        Eigen::Vector3d q;
        q(g) = across;
        q(2) = depth;
        const std::vector<double> one = arc_length(reference, f, q, options.curve_samples);
        for (size_t k = 0; k < s.size(); ++k) s[k] += one[k];
        ++curves;
      }
    for (double& x : s) x /= curves;

    std::vector<double> knots = {0.0, 1.0};
    for (double value : features[f]) {
      if (!(value > 0.0 && value < 1.0))
        throw Error("template", std::string("feature value ") + std::to_string(value) + " of " + kFieldNames[f] +
                                    " is not strictly between 0 and 1");
      knots.push_back(value);
    }
    std::sort(knots.begin(), knots.end());
    knots.erase(std::unique(knots.begin(), knots.end(), [](double a, double b) { return b - a <= kSameValue; }),
                knots.end());
    std::vector<double>& lines = grid.lines[f];
    lines.push_back(0.0);
    for (size_t k = 0; k + 1 < knots.size(); ++k) {
      const double from = length_at(s, knots[k]), to = length_at(s, knots[k + 1]);
      const int n = std::max(1, static_cast<int>(std::lround((to - from) / grid.cell_size)));
      for (int m = 1; m < n; ++m) lines.push_back(parameter_at(s, from + (to - from) * m / n));
      lines.push_back(knots[k + 1]);
    }
  }
  for (int k = 0; k <= options.layers; ++k) grid.lines[2].push_back(static_cast<double>(k) / options.layers);
  return grid;
}

VolumeMesh grid_hex_mesh(const TemplateGrid& grid, bool mirrored) {
  const int nu = grid.cells(0), nv = grid.cells(1), nw = grid.cells(2);
  VolumeMesh mesh;
  mesh.V.resize((nu + 1) * (nv + 1) * (nw + 1), 3);
  Eigen::VectorXd side_mask(mesh.V.rows());
  for (int k = 0; k <= nw; ++k)
    for (int j = 0; j <= nv; ++j)
      for (int i = 0; i <= nu; ++i) {
        const int v = vertex_id(grid, i, j, k);
        const Eigen::Vector3d uvw(grid.lines[0][i], grid.lines[1][j], grid.lines[2][k]);
        mesh.V.row(v) = mirrored ? Eigen::RowVector3d(uvw(0), uvw(2), uvw(1)) : uvw.transpose();
        side_mask(v) = grid_side_mask(grid, {i, j, k});
      }
  mesh.point_data[kSideMaskArray] = side_mask;
  // VTK's hex corner order in the embedding's axes (a, b, c), as offsets in (i, j, k): the embedding's second and
  // third axes are w and v when mirrored.
  static constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                        {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  mesh.C.resize(nu * nv * nw, 8);
  mesh.types.assign(static_cast<size_t>(nu * nv * nw), CellType::Hex);
  int c = 0;
  for (int k = 0; k < nw; ++k)
    for (int j = 0; j < nv; ++j)
      for (int i = 0; i < nu; ++i, ++c)
        for (int n = 0; n < 8; ++n) {
          const int* o = kCorner[n];
          const int dj = mirrored ? o[2] : o[1], dk = mirrored ? o[1] : o[2];
          mesh.C(c, n) = vertex_id(grid, i + o[0], j + dj, k + dk);
        }
  return mesh;
}

ConstraintSet grid_constraints(const TemplateGrid& grid, const ConstraintSet& reference_set, const Eigen::MatrixXd& V) {
  ConstraintSet set = side_constraints();
  const int nu = grid.cells(0), nv = grid.cells(1), nw = grid.cells(2);
  for (const Constraint& c : reference_set.constraints) {
    if (c.select.side) continue;
    const int line = line_index(grid.lines[c.field], c.value);
    if (line < 0)
      throw Error("template", "feature '" + c.name + "' (" + kFieldNames[c.field] + " = " + std::to_string(c.value) +
                                  ") is not a grid line");
    Constraint row{c.name, c.field, c.value, {}, c.origin};
    const std::optional<PlaneSelection>& plane = c.select.plane;
    for (int k = 0; k <= nw; ++k)
      for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) {
          const std::array<int, 3> index = {i, j, k};
          if (index[c.field] != line) continue;
          const int v = vertex_id(grid, i, j, k);
          const int mask = grid_side_mask(grid, index);  // a grid vertex is on the boundary iff on a side
          if (V.rows() > 0 && plane && !within_selection_limits(*plane, V.row(v).transpose(), mask != 0, mask))
            continue;
          row.select.ids.push_back(v);
        }
    if (row.select.ids.empty())
      throw Error("template", "feature '" + c.name + "' selects no vertex of the template's row");
    set.constraints.push_back(row);
  }
  return set;
}

// The repair's corner power (UntangleOptions::corner_power): a template has no other mesh's angles to keep, so its
// repair weighs the worst corners heavily, which raises the minimum scaled Jacobian, the bound a solver cares about.
constexpr double kRepairCornerPower = 8;

TemplateResult build_template(const VolumeMesh& reference, const ConstraintSet& reference_set,
                              const std::string& source, const TemplateOptions& options,
                              const TransferOptions& transfer, const ProgressCallback& progress) {
  check_options(options);  // before the reference's parameterization, which takes a while
  TemplateResult result;
  TransferRun& run = result.run;
  report_progress(progress, "parameterizing the reference", 0.0);
  run.patient = parameterize_model(reference.V, reference.tets(), side_mask_of(reference), reference_set, source,
                                   transfer.fields);
  report_progress(progress, "laying out the grid", 0.6);
  const PatientMap reference_map(run.patient.V, run.patient.T, run.patient.fields.uvw);
  result.grid = template_grid(reference_map, feature_lines(reference_set), options);
  const VolumeMesh grid = grid_hex_mesh(result.grid, run.patient.health.orientation < 0);
  // The grid is its own parameterization (linear fields are harmonic); whole feature rows are pinned so that the
  // repair keeps them on their features.
  const TetDomain domain = auxiliary_domain(grid);
  run.standard = parameterize_model(domain.V, domain.T, domain.side_mask, grid_constraints(result.grid, reference_set),
                                    "template grid", transfer.fields);
  report_progress(progress, "mapping the grid onto the reference", 0.7);
  // The grid's coordinates are parameters, not a shape or a correspondence to keep: the relaxation slides the
  // vertices freely along the reference towards ideal cells, and the repair weighs the worst corners most
  // (TemplateOptions).
  TransferOptions grid_transfer = transfer;
  grid_transfer.shape_relaxation = options.relax;
  grid_transfer.ideal_cell_targets = true;
  grid_transfer.relaxation_tether = 0;
  grid_transfer.untangle_options.corner_power = kRepairCornerPower;
  grid_transfer.polish_moves_sides = options.cut_sharp_corners;
  map_parameterized(run, grid, source, grid_transfer);
  result.mesh = run.patient_hex;
  result.mesh.point_data[kSideMaskArray] = grid.point_data.at(kSideMaskArray);
  result.constraints = grid_constraints(result.grid, reference_set, result.mesh.V);
  report_progress(progress, "template done", 1.0);
  return result;
}

}  // namespace facehex
