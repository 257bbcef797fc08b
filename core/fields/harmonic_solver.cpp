#include "core/fields/harmonic_solver.h"

#include <Eigen/CholmodSupport>
#include <algorithm>

#include "core/util/blas_threads.h"
#include "core/util/error.h"

namespace facehex {

struct HarmonicSolver::Factorization {
  Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower> cholmod;
};

namespace {

// The block of K with rows and columns `vertices`, in that order (position[v]: v's index in `vertices`, -1 if
// absent). Copied column by column, each column's rows then sorted: one pass over K, where S K S^T with a selection
// matrix S would take two sparse products.
SparseMatrix block(const SparseMatrix& K, const std::vector<int>& vertices, const std::vector<int>& position) {
  const auto m = static_cast<Eigen::Index>(vertices.size());
  SparseMatrix B(m, m);
  std::vector<int> start(vertices.size() + 1, 0);
  for (size_t j = 0; j < vertices.size(); ++j) {
    int count = 0;
    for (SparseMatrix::InnerIterator it(K, vertices[j]); it; ++it) count += position[it.row()] >= 0;
    start[j + 1] = start[j] + count;
  }
  B.resizeNonZeros(start.back());
  std::copy(start.begin(), start.end(), B.outerIndexPtr());
  std::vector<std::pair<int, double>> column;
  for (size_t j = 0; j < vertices.size(); ++j) {
    column.clear();
    for (SparseMatrix::InnerIterator it(K, vertices[j]); it; ++it)
      if (position[it.row()] >= 0) column.emplace_back(position[it.row()], it.value());
    std::sort(column.begin(), column.end());
    for (size_t k = 0; k < column.size(); ++k) {
      B.innerIndexPtr()[start[j] + static_cast<int>(k)] = column[k].first;
      B.valuePtr()[start[j] + static_cast<int>(k)] = column[k].second;
    }
  }
  return B;
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

  std::vector<int> position(n_, -1);
  for (size_t i = 0; i < free_.size(); ++i) position[free_[i]] = static_cast<int>(i);
  const SparseMatrix K_ff = block(K, free_, position);
  // The fixed values' contribution to every right-hand side, K_free,fixed * fixed values: K times the vector that
  // holds them, at the free rows.
  Eigen::VectorXd fixed_only = Eigen::VectorXd::Zero(n_);
  for (size_t i = 0; i < fixed_.size(); ++i) fixed_only(fixed_[i]) = fixed_values_(static_cast<Eigen::Index>(i));
  const Eigen::VectorXd K_fixed_only = K * fixed_only;
  fixed_part_.resize(static_cast<Eigen::Index>(free_.size()));
  for (size_t i = 0; i < free_.size(); ++i) fixed_part_(static_cast<Eigen::Index>(i)) = K_fixed_only(free_[i]);
  auto& cholmod = factorization_->cholmod;
  // Small systems are factored simplicial: their supernodes are short and the dense BLAS kernels' overhead dominates.
  const auto choose_kind = [&cholmod](double flops) {
    const bool simplicial = flops < kSupernodalAboveFlops;
    cholmod.cholmod().supernodal = simplicial ? CHOLMOD_SIMPLICIAL : CHOLMOD_SUPERNODAL;
    cholmod.cholmod().final_ll = simplicial ? 1 : 0;
  };
  if (options.order && options.predicted_flops) {
    choose_kind(*options.predicted_flops);
    cholmod.analyzePattern(K_ff);
  } else {
    cholmod.analyzePattern(K_ff);  // CHOLMOD's own choice (supernodal for large systems), and the flop count
    if (cholmod.info() == Eigen::Success && cholmod.cholmod().fl < kSupernodalAboveFlops) {
      choose_kind(cholmod.cholmod().fl);
      cholmod.analyzePattern(K_ff);
    }
  }
  if (cholmod.info() == Eigen::Success) {
    const SingleThreadedBlas blas;
    cholmod.factorize(K_ff);
  }
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
  b -= fixed_part_;
  const SingleThreadedBlas blas;
  const Eigen::VectorXd x = factorization_->cholmod.solve(b);
  if (factorization_->cholmod.info() != Eigen::Success || !x.allFinite())
    throw Error(name_, "the sparse solve failed (non-finite result)");
  for (size_t i = 0; i < free_.size(); ++i) u(free_[i]) = x(static_cast<Eigen::Index>(i));
  return u;
}

Eigen::VectorXd HarmonicSolver::solve_laplace() const { return solve(Eigen::VectorXd::Zero(n_)); }

}  // namespace facehex
