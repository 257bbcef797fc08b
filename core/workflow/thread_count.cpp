#include "core/workflow/thread_count.h"

#include <dlfcn.h>
#include <omp.h>
#include <vtkMultiThreader.h>
#include <vtkSMPTools.h>

#include <cstdlib>
#include <string>

namespace facehex {
namespace {

// OpenBLAS's own calls, looked up at run time: Debian's BLAS is an alternative (libblas.so.3 may be the reference BLAS,
// which has no threads and no such functions), so they cannot be linked by name.
template <typename Function>
Function* openblas_function(const char* name) {
  return reinterpret_cast<Function*>(dlsym(RTLD_DEFAULT, name));
}

}  // namespace

void set_thread_count(int threads) {
  const std::string n = std::to_string(threads);
  setenv("OMP_NUM_THREADS", n.c_str(), 1);
  setenv("OPENBLAS_NUM_THREADS", n.c_str(), 1);
  omp_set_num_threads(threads);
  if (auto* set = openblas_function<void(int)>("openblas_set_num_threads")) set(threads);
  vtkMultiThreader::SetGlobalMaximumNumberOfThreads(threads);
  vtkSMPTools::Initialize(threads);
}

ThreadCounts thread_counts() {
  ThreadCounts c;
  c.openmp = omp_get_max_threads();
  if (auto* get = openblas_function<int()>("openblas_get_num_threads")) c.openblas = get();
  c.vtk = vtkMultiThreader::GetGlobalMaximumNumberOfThreads();
  return c;
}

}  // namespace facehex
