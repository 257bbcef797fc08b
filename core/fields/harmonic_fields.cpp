#include "core/fields/harmonic_fields.h"

#include <exception>
#include <set>
#include <vector>

#include "core/util/error.h"
#include "core/util/stopwatch.h"

namespace facehex {
namespace {

// Runs job(0), ..., job(count - 1), concurrently (one per thread) when `concurrent`, and rethrows the first failure.
// Not one parallel loop with an if clause: CHOLMOD's supernodal routines run several times slower when called inside
// even an inactive OpenMP region.
template <class Job>
void run_jobs(int count, bool concurrent, const Job& job) {
  std::vector<std::exception_ptr> failure(static_cast<size_t>(count));
  const auto guarded = [&](int i) {
    try {
      job(i);
    } catch (...) {
      failure[static_cast<size_t>(i)] = std::current_exception();
    }
  };
  if (concurrent) {
#pragma omp parallel for schedule(dynamic, 1)
    for (int i = 0; i < count; ++i) guarded(i);
  } else {
    for (int i = 0; i < count; ++i) guarded(i);
  }
  for (const std::exception_ptr& e : failure)
    if (e) std::rethrow_exception(e);
}

}  // namespace

HarmonicFields::HarmonicFields(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T,
                               const ResolvedConstraints& constraints, const HarmonicFieldsOptions& options,
                               const ProgressCallback& progress)
    : options_(options) {
  const std::set<int> field_order(options.order.begin(), options.order.end());
  if (field_order != std::set<int>{0, 1, 2})
    throw Error("harmonic fields", "the field order must be a permutation of u, v, w");
  if (options.orthogonality_iterations < 0) throw Error("harmonic fields", "negative number of iterations");
  Stopwatch clock;
  report_progress(progress, "assembling the Laplacian", 0.0);
  K_ = cotangent_stiffness(V, T);
  G_ = gradient_operator(V, T);
  volumes_ = tet_volumes(V, T);
  setup_seconds_["laplacian_assembly"] = clock.lap();
  report_progress(progress, "ordering the Laplacian for factorization", 0.0);
  double factor_flops = 0;
  const auto elimination_order = std::make_shared<const std::vector<int>>(fill_reducing_order(K_, &factor_flops));
  // Small (simplicial) factorizations and their solves run concurrently, one per thread. Supernodal ones run one
  // after the other (on one BLAS thread: SingleThreadedBlas): run concurrently they compete for memory bandwidth and
  // take longer in all. With the shared order, the results do not depend on which thread factors what.
  concurrent_ = factor_flops < kSupernodalAboveFlops;
  run_jobs(3, concurrent_, [&](int f) {
    if (!concurrent_)
      report_progress(progress, std::string("factoring the ") + kFieldNames[f] + " system", (f + 1) / 4.0);
    solvers_[f] = std::make_unique<HarmonicSolver>(
        K_, constraints.fields[f], HarmonicSolver::Options{kFieldNames[f], elimination_order, factor_flops});
  });
  setup_seconds_["factorization"] = clock.lap();
}

HarmonicFields::~HarmonicFields() = default;

GradientFields HarmonicFields::gradients_of(const Eigen::MatrixXd& uvw) const {
  GradientFields g;
#pragma omp parallel for
  for (int f = 0; f < 3; ++f) g[f] = tet_gradients(G_, uvw.col(f));
  return g;
}

HarmonicFieldsResult HarmonicFields::compute(const ProgressCallback& progress) const {
  HarmonicFieldsResult r;
  r.seconds = setup_seconds_;
  Stopwatch clock;
  const Eigen::Index n = K_.rows();
  r.uvw_initial.resize(n, 3);
  run_jobs(3, concurrent_, [&](int f) { r.uvw_initial.col(f) = solvers_[f]->solve_laplace(); });
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
    run_jobs(2, concurrent_, [&](int k) {
      const int f = options_.order[static_cast<size_t>(k) + 1];
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
