#pragma once
// Dirichlet problems K u = b on a tet mesh, with one sparse Cholesky factorization (CHOLMOD) kept and reused for
// every right-hand side: the Laplace solve of a harmonic field (b = 0, paper eq. 4) and each Poisson re-solve of the
// orthogonality improvement (b = G^T M g*, eq. 6).
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/mesh/tet_laplacian.h"

namespace facehex {

// Vertices whose value is fixed, and those values (same length). Vertex ids are row indices of V.
struct DirichletConditions {
  std::vector<int> vertices;
  std::vector<double> values;
};

// A fill-reducing elimination order of all #V rows of K (CHOLMOD's pick among AMD and METIS), for sharing between
// solvers on the same K: their free-free blocks are K minus different fixed rows, and the order restricted to a
// block's rows serves it nearly as well as its own, while the symbolic analysis that finds it costs a large share of a
// factorization's time. factor_flops, if given, receives CHOLMOD's predicted flop count of factoring K in that
// order (each block's is a little less).
std::vector<int> fill_reducing_order(const SparseMatrix& K, double* factor_flops = nullptr);

// Factorizations predicted to take fewer floating-point operations than this are done simplicial (HarmonicFields
// factors the three fields' concurrently, one per core), the others supernodal (dense BLAS kernels on supernodes,
// one field after the other, on one BLAS thread: core/util/blas_threads.h). On small systems the supernodes are short and the dense kernels'
// overhead dominates, so the concurrent simplicial factorizations finish first; the bound is where the sequential
// supernodal ones catch up on 2 cores (the factorization column of docs/benchmarks.md shows the current times).
constexpr double kSupernodalAboveFlops = 2e9;

class HarmonicSolver {
 public:
  struct Options {
    std::string name = "field";  // used in error messages, e.g. "u"
    // fill_reducing_order(K), shared between solvers on the same K; empty: CHOLMOD finds one for this block.
    std::shared_ptr<const std::vector<int>> order;
    // fill_reducing_order's flop count for K in that order, if known: picks simplicial or supernodal
    // (kSupernodalAboveFlops) without a trial symbolic analysis of the block.
    std::optional<double> predicted_flops;
  };

  // Factors the free-free block of K. Throws facehex::Error(name, ...) when the conditions are empty, name a vertex
  // out of range or twice, or leave a part of the mesh with no fixed vertex (the block is then singular).
  HarmonicSolver(const SparseMatrix& K, const DirichletConditions& conditions, const Options& options);
  HarmonicSolver(const SparseMatrix& K, const DirichletConditions& conditions)
      : HarmonicSolver(K, conditions, Options{}) {}
  ~HarmonicSolver();
  HarmonicSolver(const HarmonicSolver&) = delete;
  HarmonicSolver& operator=(const HarmonicSolver&) = delete;

  // Solves K u = rhs at the free vertices with u = the fixed values at the fixed vertices (rhs is #V; its entries
  // at fixed vertices are ignored). solve_laplace() is solve(0).
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;
  Eigen::VectorXd solve_laplace() const;

  int num_free() const { return static_cast<int>(free_.size()); }
  int num_fixed() const { return static_cast<int>(fixed_.size()); }

 private:
  struct Factorization;
  std::unique_ptr<Factorization> factorization_;
  std::vector<int> free_, fixed_;
  Eigen::VectorXd fixed_values_;
  Eigen::VectorXd fixed_part_;  // K_free,fixed * the fixed values, subtracted from every right-hand side
  int n_ = 0;
  std::string name_;
};

}  // namespace facehex
