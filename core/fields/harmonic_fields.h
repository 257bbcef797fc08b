#pragma once
// The volumetric parameterization of a tet model (paper 3.2-3.3): three harmonic fields u, v, w with the shape-end
// and feature Dirichlet conditions, made closer to mutually orthogonal by the iterated projection + Poisson
// recovery. Each field's system is factored once; the initial Laplace solve and every Poisson re-solve reuse it.
//
// V is #V x 3, T is #T x 4 positively oriented; the result uvw is #V x 3 (columns u, v, w).
#include <Eigen/Core>
#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/fields/constraint_set.h"
#include "core/fields/harmonic_solver.h"
#include "core/fields/orthogonalize.h"
#include "core/util/progress.h"

namespace facehex {

struct HarmonicFieldsOptions {
  int orthogonality_iterations = 6;      // paper: six
  std::array<int, 3> order = {2, 0, 1};  // {basic, second, third}: default keeps w (depth), corrects u, then v
};

struct HarmonicFieldsResult {
  Eigen::MatrixXd uvw_initial;                  // #V x 3, harmonic fields before the orthogonality improvement
  Eigen::MatrixXd uvw;                          // #V x 3, after it
  GradientFields gradients_initial, gradients;  // per tet, #T x 3 each
  AngleStatistics angles_initial, angles;
  std::map<std::string, double> seconds;  // per stage
  std::vector<double> iteration_seconds;  // per orthogonality iteration
};

class HarmonicFields {
 public:
  // Assembles the operators and factors the three systems.
  HarmonicFields(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, const ResolvedConstraints& constraints,
                 const HarmonicFieldsOptions& options, const ProgressCallback& progress = {});
  ~HarmonicFields();

  HarmonicFieldsResult compute(const ProgressCallback& progress = {}) const;

  const SparseMatrix& stiffness() const { return K_; }
  const GradientMatrix& gradient() const { return G_; }
  const Eigen::VectorXd& volumes() const { return volumes_; }

 private:
  GradientFields gradients_of(const Eigen::MatrixXd& uvw) const;

  HarmonicFieldsOptions options_;
  SparseMatrix K_;
  GradientMatrix G_;
  Eigen::VectorXd volumes_;
  std::array<std::unique_ptr<HarmonicSolver>, 3> solvers_;
  bool concurrent_ = false;  // small (simplicial) factorizations: factored and solved one per thread
  std::map<std::string, double> setup_seconds_;
};

}  // namespace facehex
