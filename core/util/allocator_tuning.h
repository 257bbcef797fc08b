#pragma once
// Process-wide allocator settings for the engine's allocation pattern, called first thing by both mains.

namespace facehex {

// Makes glibc's malloc serve every allocation, from every thread, from its one main heap and never give freed memory
// back to the system (mallopt: M_MMAP_MAX = 0, M_TRIM_THRESHOLD = max, M_ARENA_MAX = 1). By default, blocks over
// 128 kB (triplet lists, factors, gradient fields) get fresh pages from the kernel on each allocation, and each
// thread allocates in an arena of its own; every fresh page then costs a fault on first touch, which is expensive on
// virtual machines, and the engine allocates and frees such blocks step after step. The peak resident size does not
// change: the heap keeps what the largest step needed and reuses it.
// Where the kernel offers transparent huge pages on request (madvise, Debian's default), the first kHugePageHeap
// bytes of the heap ask for them (as glibc's tunable glibc.malloc.hugetlb=1 would): first touches then fault once per
// 2 MB page rather than once per 4 kB page. No effect elsewhere.
constexpr long kHugePageHeap = 1L << 30;
void keep_freed_memory_for_reuse();

}  // namespace facehex
