#include "core/util/allocator_tuning.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

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

// The VmFlags of the mapping holding `address`, from /proc/self/smaps ("" if not found).
std::string mapping_flags(const void* address) {
  const auto a = reinterpret_cast<std::uintptr_t>(address);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream range(line);
    if (range >> std::hex >> lo >> dash >> hi && dash == '-') inside = lo <= a && a < hi;
    if (inside && line.rfind("VmFlags:", 0) == 0) return line;
  }
  return "";
}

TEST(AllocatorTuning, TheHeapAsksForTransparentHugePages) {
#if !defined(__GLIBC__)
  GTEST_SKIP() << "the setting is glibc's";
#else
  std::string thp;
  std::getline(std::ifstream("/sys/kernel/mm/transparent_hugepage/enabled"), thp);
  if (thp.find("[madvise]") == std::string::npos && thp.find("[always]") == std::string::npos)
    GTEST_SKIP() << "transparent huge pages are off here: " << thp;
  keep_freed_memory_for_reuse();
  constexpr size_t kBlock = size_t(64) << 20;
  auto block = std::make_unique<char[]>(kBlock);
  const std::string flags = mapping_flags(block.get() + kBlock / 2);
  ASSERT_FALSE(flags.empty());
  EXPECT_NE(flags.find(" hg"), std::string::npos) << flags;  // hg: madvise(MADV_HUGEPAGE)
#endif
}

}  // namespace
}  // namespace facehex
