#include "core/harmonic_fields.h"

#include "core/error.h"
#include "core/stopwatch.h"

#include <functional>
#include <future>
#include <set>

namespace facehex {
namespace {

// Runs work(f) for the given fields concurrently (they write disjoint columns) and rethrows the first error.
void for_each_field(std::initializer_list<int> fields, const std::function<void(int)>& work) {
  std::vector<std::future<void>> running;
  for (int f : fields) running.push_back(std::async(std::launch::async, work, f));
  for (auto& r : running) r.get();
}

}  // namespace

HarmonicFields::HarmonicFields(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T,
                               const ResolvedConstraints& constraints, const HarmonicFieldsOptions& options,
                               const ProgressCallback& progress)
    : options_(options) {
  const std::set<int> order(options.order.begin(), options.order.end());
  if (order != std::set<int>{0, 1, 2}) throw Error("harmonic fields", "the field order must be a permutation of u, v, w");
  if (options.orthogonality_iterations < 0) throw Error("harmonic fields", "negative number of iterations");
  Stopwatch clock;
  report_progress(progress, "assembling the Laplacian", 0.0);
  K_ = cotangent_stiffness(V, T);
  G_ = gradient_operator(V, T);
  volumes_ = tet_volumes(V, T);
  setup_seconds_["laplacian_assembly"] = clock.lap();
  // The three factorizations are independent (each CHOLMOD object has its own workspace): run them side by side.
  report_progress(progress, "factoring the u, v, w systems", 0.0);
  std::array<std::future<std::unique_ptr<HarmonicSolver>>, 3> factoring;
  for (int f = 0; f < 3; ++f)
    factoring[f] = std::async(std::launch::async, [this, &constraints, f] {
      return std::make_unique<HarmonicSolver>(K_, constraints.fields[f], HarmonicSolver::Options{kFieldNames[f]});
    });
  for (int f = 0; f < 3; ++f) solvers_[f] = factoring[f].get();  // rethrows a factorization's error
  setup_seconds_["factorization"] = clock.lap();
}

HarmonicFields::~HarmonicFields() = default;

GradientFields HarmonicFields::gradients_of(const Eigen::MatrixXd& uvw) const {
  GradientFields g;
  for (int f = 0; f < 3; ++f) g[f] = tet_gradients(G_, uvw.col(f));
  return g;
}

HarmonicFieldsResult HarmonicFields::compute(const ProgressCallback& progress) const {
  HarmonicFieldsResult r;
  r.seconds = setup_seconds_;
  Stopwatch clock;
  const Eigen::Index n = K_.rows();
  r.uvw_initial.resize(n, 3);
  for_each_field({0, 1, 2}, [&](int f) { r.uvw_initial.col(f) = solvers_[f]->solve_laplace(); });
  r.seconds["harmonic_solves"] = clock.lap();
  r.gradients_initial = gradients_of(r.uvw_initial);
  r.angles_initial = angle_statistics(gradient_angles(r.gradients_initial));

  r.uvw = r.uvw_initial;
  r.gradients = r.gradients_initial;
  // Right-hand side G^T M g* of eq. 6, with M the tet volumes repeated per gradient component.
  Eigen::VectorXd mass(3 * volumes_.size());
  for (Eigen::Index t = 0; t < volumes_.size(); ++t) mass.segment<3>(3 * t).setConstant(std::abs(volumes_(t)));
  Stopwatch iteration_clock;
  for (int it = 0; it < options_.orthogonality_iterations; ++it) {
    report_progress(progress, "orthogonality improvement", static_cast<double>(it) / options_.orthogonality_iterations);
    const GradientFields targets = orthogonal_targets(r.gradients, options_.order);
    // The basic field's target is its own gradient: its Poisson solve would return it unchanged, so it is skipped.
    for_each_field({options_.order[1], options_.order[2]}, [&](int f) {
      const Eigen::VectorXd g = Eigen::Map<const Eigen::VectorXd>(
          Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>(targets[f]).data(), 3 * targets[f].rows());
      r.uvw.col(f) = solvers_[f]->solve(G_.transpose() * mass.cwiseProduct(g));
    });
    r.gradients = gradients_of(r.uvw);
    r.iteration_seconds.push_back(iteration_clock.lap());
  }
  r.seconds["orthogonality_improvement"] = clock.lap();
  r.angles = angle_statistics(gradient_angles(r.gradients));
  report_progress(progress, "orthogonality improvement", 1.0);
  return r;
}

}  // namespace facehex
