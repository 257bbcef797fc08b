#pragma once
// Discrete operators on a tetrahedral mesh (paper eq. 2-3, 5-6).
//
// Inputs: V (#V x 3), T (#T x 4, positively oriented, see mesh.h).
//
// With P1 (piecewise linear) hat functions, the stiffness matrix K = G^T M G has, for an edge ij,
//   K_ij = -w_ij,   w_ij = 1/6 * sum over the tets around ij of l_k * cot(theta_k)
// where l_k is the length of the edge opposite to ij in tet k and theta_k the dihedral angle at that opposite edge
// (Liao et al., the paper's eq. 2), and K_ii = sum_j w_ij, so K annihilates constants. The paper's normalized
// operator is L = D^-1 K with D = diag(|Omega_i|), the per-vertex dual-cell volume. For a Dirichlet problem
// D^-1 K u = D^-1 b and K u = b have the same solution (D is a positive diagonal scaling of each row), so the solvers
// factor the symmetric K; normalized_laplacian() exists to evaluate the paper's operator itself.
//
// G is the gradient operator, 3#T x #V: rows 3t..3t+2 hold grad(phi_j) on tet t, so (G u) gives each tet's constant
// gradient. M is the 3#T x 3#T diagonal "mass" matrix of tet volumes (each repeated three times).
// The operators are consistent: the Poisson system K u = G^T M g returns u exactly when g = G u (eq. 6).
#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace facehex {

using SparseMatrix = Eigen::SparseMatrix<double>;
// G is stored by rows (each has the 4 entries of one tet's gradient component): it is built straight into its
// arrays, and G u, the product of every iteration, runs along rows.
using GradientMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// Signed volumes (#T), positive for positively oriented tets.
Eigen::VectorXd tet_volumes(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T);

// Gradient operator G (3#T x #V).
GradientMatrix gradient_operator(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T);

// Cotangent stiffness matrix K (#V x #V, symmetric positive semi-definite, rows sum to zero).
SparseMatrix cotangent_stiffness(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T);

// Barycentric dual-cell volumes |Omega_i| (#V): a quarter of the volume of every incident tet. They sum to the mesh
// volume; we use them for the paper's Voronoi-cell normalization (the barycentric cell is the robust stand-in for the
// circumcentric Voronoi cell, which has negative parts on obtuse tets).
Eigen::VectorXd dual_volumes(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T);

// The paper's normalized Laplacian L = D^-1 K (eq. 2-3).
SparseMatrix normalized_laplacian(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T);

// Per-tet gradients of a scalar field as #T x 3 rows (the same numbers as G u, reshaped).
Eigen::MatrixXd tet_gradients(const GradientMatrix& G, const Eigen::VectorXd& u);

}  // namespace facehex
