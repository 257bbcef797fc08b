// The thread count of every threaded library (core/workflow/thread_count.h).
#include "core/workflow/thread_count.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace facehex {
namespace {

// Every threaded library runs with the count asked for, and processes started later inherit it.
TEST(ThreadCount, SetsOpenMpOpenBlasAndVtk) {
  for (const int n : {1, 2}) {
    set_thread_count(n);
    const ThreadCounts c = thread_counts();
    EXPECT_EQ(c.openmp, n);
    EXPECT_EQ(c.vtk, n);
    EXPECT_EQ(c.openblas, n);  // scripts/install-deps.sh installs OpenBLAS, which Debian then prefers as its BLAS
    EXPECT_EQ(std::string(std::getenv("OMP_NUM_THREADS")), std::to_string(n));
    EXPECT_EQ(std::string(std::getenv("OPENBLAS_NUM_THREADS")), std::to_string(n));
  }
}

}  // namespace
}  // namespace facehex
