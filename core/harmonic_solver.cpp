#include "core/harmonic_solver.h"

#include <Eigen/CholmodSupport>
#include <algorithm>

#include "core/error.h"

namespace facehex {

struct HarmonicSolver::Factorization {
  Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower> cholmod;
};

namespace {

// Selection matrix S (rows.size() x n) with S(i, rows[i]) = 1, so S A S^T extracts a block.
SparseMatrix selection(const std::vector<int>& rows, int n) {
  SparseMatrix S(static_cast<Eigen::Index>(rows.size()), n);
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(rows.size());
  for (size_t i = 0; i < rows.size(); ++i) t.emplace_back(static_cast<int>(i), rows[i], 1.0);
  S.setFromTriplets(t.begin(), t.end());
  return S;
}

// True when every vertex is joined, through the nonzero pattern of K, to at least one fixed vertex (otherwise the
// free block is singular: that part of the field would be determined only up to a constant).
bool every_vertex_reaches_a_fixed_one(const SparseMatrix& K, const std::vector<int>& fixed) {
  std::vector<char> reached(K.rows(), 0);
  std::vector<int> stack(fixed.begin(), fixed.end());
  for (int v : fixed) reached[v] = 1;
  while (!stack.empty()) {
    const int v = stack.back();
    stack.pop_back();
    for (SparseMatrix::InnerIterator it(K, v); it; ++it)
      if (!reached[it.index()]) {
        reached[it.index()] = 1;
        stack.push_back(static_cast<int>(it.index()));
      }
  }
  return std::all_of(reached.begin(), reached.end(), [](char r) { return r != 0; });
}

bool is_permutation_of_rows(const std::vector<int>& order, int n) {
  if (static_cast<int>(order.size()) != n) return false;
  std::vector<char> seen(n, 0);
  for (int v : order) {
    if (v < 0 || v >= n || seen[v]) return false;
    seen[v] = 1;
  }
  return true;
}

}  // namespace

std::vector<int> fill_reducing_order(const SparseMatrix& K, double* factor_flops) {
  cholmod_common common;
  cholmod_start(&common);
  SparseMatrix lower = K.triangularView<Eigen::Lower>();
  cholmod_sparse A = Eigen::viewAsCholmod(lower);
  A.stype = -1;  // symmetric, lower triangle stored
  cholmod_factor* L = cholmod_analyze(&A, &common);
  std::vector<int> order;
  if (L != nullptr) {
    const int* perm = static_cast<const int*>(L->Perm);
    order.assign(perm, perm + L->n);
    if (factor_flops != nullptr) *factor_flops = common.fl;
    cholmod_free_factor(&L, &common);
  }
  cholmod_finish(&common);
  if (order.empty()) throw Error("sparse Cholesky", "CHOLMOD could not order the stiffness matrix");
  return order;
}

HarmonicSolver::HarmonicSolver(const SparseMatrix& K, const DirichletConditions& conditions, const Options& options)
    : factorization_(std::make_unique<Factorization>()), n_(static_cast<int>(K.rows())), name_(options.name) {
  if (conditions.vertices.size() != conditions.values.size())
    throw Error(name_, "Dirichlet vertices and values differ in number");
  if (conditions.vertices.empty()) throw Error(name_, "no Dirichlet condition: the field is undetermined");
  std::vector<int> slot(n_, -1);
  fixed_values_.resize(static_cast<Eigen::Index>(conditions.vertices.size()));
  for (size_t i = 0; i < conditions.vertices.size(); ++i) {
    const int v = conditions.vertices[i];
    if (v < 0 || v >= n_) throw Error(name_, "Dirichlet vertex " + std::to_string(v) + " is out of range");
    if (slot[v] != -1) throw Error(name_, "Dirichlet vertex " + std::to_string(v) + " is given twice");
    slot[v] = static_cast<int>(fixed_.size());
    fixed_.push_back(v);
    fixed_values_(static_cast<Eigen::Index>(i)) = conditions.values[i];
  }
  if (options.order) {
    if (!is_permutation_of_rows(*options.order, n_))
      throw Error(name_, "the shared elimination order is not a permutation of the mesh's vertices");
    // Free vertices in the shared order, and CHOLMOD told to keep it (its postorder does not change the fill).
    for (int v : *options.order)
      if (slot[v] == -1) free_.push_back(v);
    factorization_->cholmod.cholmod().nmethods = 1;
    factorization_->cholmod.cholmod().method[0].ordering = CHOLMOD_NATURAL;
  } else {
    for (int v = 0; v < n_; ++v)
      if (slot[v] == -1) free_.push_back(v);
  }
  if (free_.empty()) return;
  if (!every_vertex_reaches_a_fixed_one(K, fixed_))
    throw Error(name_, "part of the mesh is not connected to any Dirichlet vertex of this field");

  const SparseMatrix Sf = selection(free_, n_), Sc = selection(fixed_, n_);
  const SparseMatrix K_ff = Sf * K * Sf.transpose();
  K_free_fixed_ = Sf * K * Sc.transpose();
  auto& cholmod = factorization_->cholmod;
  cholmod.analyzePattern(K_ff);
  if (cholmod.info() == Eigen::Success && cholmod.cholmod().fl < kSupernodalAboveFlops) {
    // Small systems: supernodes are short and the dense BLAS kernels' overhead dominates.
    cholmod.cholmod().supernodal = CHOLMOD_SIMPLICIAL;
    cholmod.cholmod().final_ll = 1;
    cholmod.analyzePattern(K_ff);
  }
  if (cholmod.info() == Eigen::Success) cholmod.factorize(K_ff);
  if (cholmod.info() != Eigen::Success)
    throw Error(name_, "the sparse Cholesky factorization failed (the stiffness matrix is not positive definite)");
}

HarmonicSolver::~HarmonicSolver() = default;

Eigen::VectorXd HarmonicSolver::solve(const Eigen::VectorXd& rhs) const {
  Eigen::VectorXd u(n_);
  for (size_t i = 0; i < fixed_.size(); ++i) u(fixed_[i]) = fixed_values_(static_cast<Eigen::Index>(i));
  if (free_.empty()) return u;
  Eigen::VectorXd b(static_cast<Eigen::Index>(free_.size()));
  for (size_t i = 0; i < free_.size(); ++i) b(static_cast<Eigen::Index>(i)) = rhs(free_[i]);
  b -= K_free_fixed_ * fixed_values_;
  const Eigen::VectorXd x = factorization_->cholmod.solve(b);
  if (factorization_->cholmod.info() != Eigen::Success || !x.allFinite())
    throw Error(name_, "the sparse solve failed (non-finite result)");
  for (size_t i = 0; i < free_.size(); ++i) u(free_[i]) = x(static_cast<Eigen::Index>(i));
  return u;
}

Eigen::VectorXd HarmonicSolver::solve_laplace() const { return solve(Eigen::VectorXd::Zero(n_)); }

}  // namespace facehex
