#include "core/util/blas_threads.h"

#include <dlfcn.h>

namespace facehex {
namespace {

template <typename Function>
Function* openblas_function(const char* name) {
  return reinterpret_cast<Function*>(dlsym(RTLD_DEFAULT, name));
}

}  // namespace

int blas_threads() {
  auto* get = openblas_function<int()>("openblas_get_num_threads");
  return get ? get() : 0;
}

void set_blas_threads(int threads) {
  if (auto* set = openblas_function<void(int)>("openblas_set_num_threads")) set(threads);
}

SingleThreadedBlas::SingleThreadedBlas() : before_(blas_threads()) {
  if (before_ > 1) set_blas_threads(1);
}

SingleThreadedBlas::~SingleThreadedBlas() {
  if (before_ > 1) set_blas_threads(before_);
}

}  // namespace facehex
