// One libFuzzer target: the reader named by FACEHEX_FUZZ_READER (tests/fuzz/CMakeLists.txt builds one binary per
// reader). At exit it prints the peak RSS of the child processes the readers forked, which libFuzzer's own figure
// (this process only) leaves out.
#include <pthread.h>
#include <sanitizer/asan_interface.h>
#include <sanitizer/common_interface_defs.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "tests/fuzz/fuzz_readers.h"

namespace {

std::string g_dir;

void report_children_and_clean_up() {
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  std::fprintf(stderr, "facehex_fuzz: children peak RSS %ld MB\n", usage.ru_maxrss / 1024);
  std::error_code ec;
  std::filesystem::remove_all(g_dir, ec);
}

// A bad memory access ASan found in our own code inside a reading child is a finding: the parent, signalled, records
// the input. Running out of the child's memory budget (ASan reports it, with no address, rather than throwing
// std::bad_alloc) is not.
void child_death() {
  if (__asan_report_present() && __asan_get_report_address() != nullptr) kill(getppid(), SIGABRT);
}

// In a reading child, a crash inside VTK or a runaway allocation is the product's contained case (the parent reports
// it as an error naming the file): the child dies as it would outside the fuzzer, instead of being recorded as a
// finding by the handlers libFuzzer and ASan installed.
void contain_crashes_in_child() {
  for (const int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) signal(sig, SIG_DFL);
  __sanitizer_set_death_callback(child_death);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  pthread_atfork(nullptr, nullptr, contain_crashes_in_child);
  std::string pattern = (std::filesystem::temp_directory_path() / "facehex_fuzz_XXXXXX").string();
  if (!mkdtemp(pattern.data())) std::abort();
  g_dir = pattern;
  std::atexit(report_children_and_clean_up);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  facehex::fuzz::read_input(FACEHEX_FUZZ_READER, data, size, g_dir);
  return 0;
}
