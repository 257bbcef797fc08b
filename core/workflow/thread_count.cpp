#include "core/workflow/thread_count.h"

#include <omp.h>
#include <vtkMultiThreader.h>
#include <vtkSMPTools.h>

#include <cstdlib>
#include <string>

#include "core/util/blas_threads.h"

namespace facehex {

void set_thread_count(int threads) {
  const std::string n = std::to_string(threads);
  setenv("OMP_NUM_THREADS", n.c_str(), 1);
  setenv("OPENBLAS_NUM_THREADS", n.c_str(), 1);
  omp_set_num_threads(threads);
  set_blas_threads(threads);
  vtkMultiThreader::SetGlobalMaximumNumberOfThreads(threads);
  vtkSMPTools::Initialize(threads);
}

ThreadCounts thread_counts() {
  ThreadCounts c;
  c.openmp = omp_get_max_threads();
  c.openblas = blas_threads();
  c.vtk = vtkMultiThreader::GetGlobalMaximumNumberOfThreads();
  return c;
}

}  // namespace facehex
