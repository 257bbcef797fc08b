#pragma once
// Constraint sets: the Dirichlet conditions of the three parameterization fields, as a JSON file a person can read
// and edit. Each constraint pins a set of vertices of one field to one value: the shape ends (0 and 1, paper 3.2) and
// the piecewise feature constraints (e.g. 0.5 on the mid-sagittal line, paper 3.4).
//
// File format (version 1):
// {
//   "format": "facehex-constraints", "version": 1,
//   "constraints": [
//     {"name": "outer (skin)", "field": "w", "value": 1, "select": {"side": "w1"}},
//     {"name": "mid-sagittal", "field": "u", "value": 0.5,
//      "select": {"plane": {"point": [0, 0, 0], "normal": [1, 0, 0]}, "band": 1.0, "region": "volume",
//                 "within": {"center": [0, 80, -60], "radius": 40}}},
//     {"name": "picked", "field": "v", "value": 0.7, "select": {"ids": [12, 13, 14]}}
//   ]
// }
// Selections:
//  - "ids":   explicit vertex ids (0-based row indices of the model's V).
//  - "side":  every vertex whose point-data "side_mask" has that side's bit (see sides.h).
//  - "plane": every vertex within band/2 (mm, default 1) of the plane, restricted to "region": "volume" (all
//             vertices, the default), "boundary" (boundary vertices), or a side name; optionally only those within
//             "within".radius of "within".center, and not those on the sides listed in "exclude" (e.g. a feature
//             line of v stops where it meets the top or bottom cut). A geometric selection re-applies to a remeshed
//             model.
#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/fields/harmonic_solver.h"
#include "core/mesh/mesh.h"
#include "core/mesh/sides.h"

namespace facehex {

constexpr std::array<const char*, 3> kFieldNames = {"u", "v", "w"};

struct PlaneSelection {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  double band = 1.0;              // mm, full width of the slab
  std::string region = "volume";  // "volume", "boundary" or a side name
  std::optional<Eigen::Vector3d> within_center;
  double within_radius = 0;
  int exclude_sides = 0;  // side bits: vertices on these sides are not selected
};

struct Selection {
  std::vector<int> ids;
  std::optional<Side> side;
  std::optional<PlaneSelection> plane;
};

struct Constraint {
  std::string name;
  int field = 0;  // 0 = u, 1 = v, 2 = w
  double value = 0;
  Selection select;
  std::string origin;  // for messages: what placed it (e.g. the landmark it sits at); not written to files
};

struct ConstraintSet {
  std::vector<Constraint> constraints;
};

// Parsing and writing; errors name `source` (the file) and the offending constraint.
ConstraintSet parse_constraint_set(const std::string& json_text, const std::string& source);
ConstraintSet read_constraint_set(const std::string& path);
std::string to_json(const ConstraintSet& set);
void write_constraint_set(const std::string& path, const ConstraintSet& set);  // atomically

// The six shape-end constraints selecting the sides by "side_mask" (the default for models that carry it).
ConstraintSet side_constraints();

// Whether a vertex at x (on the boundary or not, with side bits side_mask) passes a plane selection's restrictions
// other than its plane and band: the region, the "within" sphere and the excluded sides.
bool within_selection_limits(const PlaneSelection& p, const Eigen::Vector3d& x, bool on_boundary, int side_mask);

// Vertices each constraint selects on a tet model (V #V x 3, T #T x 4, side_mask #V or empty).
std::vector<int> select_vertices(const Selection& selection, const Eigen::MatrixXd& V,
                                 const std::vector<char>& boundary_flags, const Eigen::VectorXi& side_mask);

// The Dirichlet conditions of the three fields. Throws facehex::Error(source, ...) when a constraint selects no
// vertex, a vertex gets two different values in one field, a field lacks its 0 end or its 1 end, or a side selection
// is used on a model without "side_mask".
struct ResolvedConstraints {
  std::array<DirichletConditions, 3> fields;
  std::vector<std::vector<int>> selected;  // per constraint, the vertices it selected
};
ResolvedConstraints resolve_constraints(const ConstraintSet& set, const Eigen::MatrixXd& V, const Eigen::MatrixXi& T,
                                        const Eigen::VectorXi& side_mask, const std::string& source);

// The "side_mask" point-data array of a mesh as integers (#V), or an empty vector when absent.
Eigen::VectorXi side_mask_of(const VolumeMesh& mesh);

}  // namespace facehex
