#include "core/util/allocator_tuning.h"

#include <climits>
#include <cstdint>
#include <cstdlib>

#if defined(__GLIBC__)
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace facehex {

void keep_freed_memory_for_reuse() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, INT_MAX);
  mallopt(M_ARENA_MAX, 1);
#if defined(MADV_HUGEPAGE)
  // Grow the heap by kHugePageHeap of address space up front (a block from the heap, freed at once and not trimmed; its
  // untouched pages cost nothing) and ask for transparent huge pages there.
  constexpr std::uintptr_t kHugePage = std::uintptr_t(2) << 20;
  void* block = std::malloc(static_cast<size_t>(kHugePageHeap));
  if (block == nullptr) return;
  const auto start = (reinterpret_cast<std::uintptr_t>(block) + kHugePage - 1) & ~(kHugePage - 1);
  std::free(block);
  const auto end = reinterpret_cast<std::uintptr_t>(sbrk(0));
  if (end > start) madvise(reinterpret_cast<void*>(start), end - start, MADV_HUGEPAGE);
#endif
#endif
}

}  // namespace facehex
