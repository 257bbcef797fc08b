#include "core/allocator_tuning.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <memory>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace facehex {
namespace {

TEST(AllocatorTuning, LargeBlocksComeFromTheHeapAndStayWithTheProcess) {
#if !defined(__GLIBC__)
  GTEST_SKIP() << "the setting is glibc's";
#else
  keep_freed_memory_for_reuse();
  constexpr size_t kBlock = size_t(64) << 20;  // far above glibc's default mmap threshold of 128 kB
  const size_t mapped_before = mallinfo2().hblks;
  {
    auto block = std::make_unique<char[]>(kBlock);
    block[0] = block[kBlock - 1] = 1;
    EXPECT_EQ(mallinfo2().hblks, mapped_before);  // not a fresh mapping of its own
  }
  EXPECT_GE(mallinfo2().arena, kBlock);  // freed, but the heap was not trimmed: the next step reuses the pages
#endif
}

}  // namespace
}  // namespace facehex
