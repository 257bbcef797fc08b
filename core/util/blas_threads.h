#pragma once
// OpenBLAS's thread count, read and set at run time: Debian's BLAS is an alternative (libblas.so.3 may be the
// reference BLAS, which has no threads and no such calls), so the calls are looked up, not linked.

namespace facehex {

// 0 when the BLAS in use is not OpenBLAS.
int blas_threads();
// No effect when the BLAS in use is not OpenBLAS.
void set_blas_threads(int threads);

// While it lives, BLAS runs on one thread; the count is restored when it ends. For the sparse factorizations and
// solves: OpenBLAS's threads wait for each other by spinning, so one that waits for a core stalls every kernel (a
// factorization shared with one other job ran several times slower than on one thread), and the factors' rounding
// depends on the thread count (the same input would give other fields on a busier machine). On a few cores a second
// BLAS thread gains little (docs/benchmarks.md).
class SingleThreadedBlas {
 public:
  SingleThreadedBlas();
  ~SingleThreadedBlas();
  SingleThreadedBlas(const SingleThreadedBlas&) = delete;
  SingleThreadedBlas& operator=(const SingleThreadedBlas&) = delete;

 private:
  int before_;
};

}  // namespace facehex
