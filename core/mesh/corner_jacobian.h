#pragma once
// Corner Jacobians of linear tets, wedges and hexes (VTK node order, see mesh.h): the inversion test of the mapped
// mesh, the wedge scaled Jacobian, and the per-corner terms an untangling optimizer works on.
//
// Corner k of a cell is its node k. Its corner matrix A_k (3 x 3) has as COLUMNS the three edge vectors leaving
// node k, A_k = [x_a - x_k, x_b - x_k, x_c - x_k], with (k; a, b, c) = corner_nodes(type, k) ordered so that
//
//     det(A_k) > 0  <=>  the cell is positively oriented at that corner (mesh.h conventions);
//
// the unit cube hex gives A_k a signed permutation of the identity and det(A_k) = +1 at every corner. A mirrored
// (negatively oriented) cell gives det(A_k) < 0 at every corner; a cell with a node pushed through the opposite face
// gives det(A_k) <= 0 at some corners. A cell is INVERTED if any corner has det(A_k) <= 0, or any interior sample
// point (below) a non-positive Jacobian.
//
// Corners per type: hex 8 (the three edges of the node), wedge 6 (two triangle edges, then the edge to the other
// triangle), tet 4 (det(A_k) = 6 * volume at every corner, but the edge lengths, hence the scaled Jacobian, differ).
#include <Eigen/Core>
#include <array>
#include <vector>

#include "core/mesh/mesh.h"

namespace facehex {

// Node positions of one cell: rows 0 .. node_count(type)-1 used, in VTK order. Fixed size so per-cell work does not
// allocate.
using CellNodes = Eigen::Matrix<double, 8, 3>;
// Per-corner values of one cell: entries 0 .. node_count(type)-1 used.
using CornerValues = Eigen::Matrix<double, 8, 1>;

// The ideal cell of each type, unit edges, positively oriented, rows in VTK order: the unit cube [0,1]^3; the prism
// of height 1 over the equilateral triangle (0,0,0), (1/2,sqrt(3)/2,0), (1,0,0) (z = 0, then z = 1); the regular tet
// (0,0,0), (1,0,0), (1/2,sqrt(3)/2,0), apex above. Quality measures are normalized so that it scores 1.
CellNodes ideal_cell(CellType type);

// Gathers the nodes of `cell` (an index into mesh.C) from mesh.V.
CellNodes cell_nodes(const VolumeMesh& mesh, int cell);

// Local node ids (k, a, b, c) of corner k: A_k = [x_a - x_k, x_b - x_k, x_c - x_k]. k < node_count(type).
const std::array<int, 4>& corner_nodes(CellType type, int k);

// A_k, 3 x 3, edge vectors as columns.
Eigen::Matrix3d corner_jacobian(CellType type, const CellNodes& X, int k);

// Interior sample points, where solvers evaluate the element Jacobian: for a hex its centre (Verdict's ninth sample)
// then the 2x2x2 Gauss points; for a wedge the triangle's 3-point rule and centroid, each at the two Gauss points
// through the thickness; none for a tet (its Jacobian is constant). A cell can be inverted at such a point with all
// its corners positive (CalculiX rejects it), so the inversion test includes them. Each sample's Jacobian is linear in
// the nodes, J_s = X^T W_s (W_s: rows 0 .. node_count(type)-1 used), with W_s normalized so that the ideal cell has
// J_s = I at every sample: det(J_s) > 0 <=> positively oriented there.
using SampleWeights = Eigen::Matrix<double, 8, 3>;
const std::vector<SampleWeights>& interior_sample_weights(CellType type);

// The Jacobian at the centre of a hex (its first interior sample): columns are the mean edge vectors along its three
// axes, (x1+x2+x5+x6 - x0-x3-x4-x7)/4 etc.; the unit cube gives the identity. The scaled Jacobian includes it, as
// Verdict's.
Eigen::Matrix3d hex_center_jacobian(const CellNodes& X);

// det(A_k) for k = 0 .. node_count(type)-1.
CornerValues corner_determinants(CellType type, const CellNodes& X);

// The smallest Jacobian determinant over the corners (det A_k) and the interior samples (det J_s).
double min_corner_determinant(CellType type, const CellNodes& X);

// min_corner_determinant and scaled_jacobian (below) of one cell in one pass: they share the corner matrices.
struct CellJacobians {
  double min_determinant = 0;
  double scaled_jacobian = 0;
};
CellJacobians cell_jacobians(CellType type, const CellNodes& X);

// Scaled Jacobian: s * min over corners of det(A_k) / (|a_1| |a_2| |a_3|), a_i the columns of A_k, in [-1, 1].
// The factor s makes the ideal element score exactly 1:
//   hex   s = 1        (any box; a corner with three orthogonal edges gives 1),
//   wedge s = 2/sqrt(3) (the EQUILATERAL-triangle prism with edges orthogonal to the triangles; a right-triangle
//                        prism scores sqrt(2/3) ~ 0.816 because of its two 45 degree corners),
//   tet   s = sqrt(2)   (the regular tet), as Verdict does for tets.
// A corner with a zero-length edge counts as 0 (degenerate).
double scaled_jacobian(CellType type, const CellNodes& X);

// A cell whose scaled Jacobian is below this, without being inverted, is DEGENERATE (flat): as unusable in a solver.
constexpr double kDegenerateScaledJacobian = 1e-6;

// Inverted or degenerate.
bool is_unusable(const CellJacobians& j);
bool is_unusable(CellType type, const CellNodes& X);

// Corner Jacobian check of a whole mesh.
struct CornerJacobianCheck {
  Eigen::VectorXd min_determinant;    // #C, min_corner_determinant of each cell (mm^3)
  std::vector<int> inverted;          // ascending ids of the cells with det(A_k) or det(J_s) <= 0
  std::vector<int> degenerate;        // ascending ids of the cells not inverted, scaled Jacobian < 1e-6
  std::vector<int> unusable() const;  // inverted and degenerate, ascending
};

CornerJacobianCheck check_corner_jacobians(const VolumeMesh& mesh);

}  // namespace facehex
