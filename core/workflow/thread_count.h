#pragma once
// How many threads one FaceHex process computes with, set once for every threaded library it runs: our own OpenMP
// loops (core/mesh, fields, mapping, evaluation, segment), OpenBLAS under CHOLMOD's supernodal factorization, and VTK's
// threaded imaging filters in the segmentation. Eigen is built single-threaded (EIGEN_DONT_PARALLELIZE) and needs no
// setting. Cohorts run several processes side by side, so that N jobs x threads fit the machine (docs/cohorts.md).
namespace facehex {

struct ThreadCounts {
  int openmp = 0;    // omp_get_max_threads()
  int openblas = 0;  // openblas_get_num_threads(), or 0 when the BLAS in use is not OpenBLAS
  int vtk = 0;       // vtkMultiThreader's global maximum (0: VTK's own default)
};

// Every library's count to `threads` (>= 1), also in the environment (OMP_NUM_THREADS, OPENBLAS_NUM_THREADS) for the
// processes this one starts. Call it before the work starts.
void set_thread_count(int threads);

ThreadCounts thread_counts();

}  // namespace facehex
