// Work in a child process: its result comes back whole, its facehex::Error comes back as it was, and a crash, a hang
// or a runaway allocation become an Error that says which, while the parent carries on.
#include "core/util/child_process.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <fstream>
#include <memory>
#include <thread>

#include "core/util/error.h"

namespace facehex {
namespace {

std::string error_of(const std::function<std::vector<char>()>& work, const ChildLimits& limits = {}) {
  try {
    compute_in_child("subject.vtu", "reading", work, limits);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ChildProcess, AResultLargerThanThePipeComesBackWhole) {
  std::vector<char> big(5 << 20);
  for (size_t i = 0; i < big.size(); ++i) big[i] = static_cast<char>(i * 7919 % 251);
  EXPECT_EQ(compute_in_child("s", "copying", [&] { return big; }, {}), big);
  EXPECT_TRUE(compute_in_child("s", "nothing", [] { return std::vector<char>(); }, {}).empty());
}

TEST(ChildProcess, AnErrorThrownThereIsThrownHereAsItWas) {
  EXPECT_EQ(error_of([]() -> std::vector<char> { throw Error("other.vtu", "NumberOfPoints is -1"); }),
            "other.vtu: NumberOfPoints is -1");
  EXPECT_EQ(error_of([]() -> std::vector<char> { throw Error("", "no subject"); }), "no subject");
}

TEST(ChildProcess, ACrashIsAnErrorNamingTheSignal) {
  const std::string e = error_of([]() -> std::vector<char> {
    ::raise(SIGSEGV);
    return {};
  });
  EXPECT_NE(e.find("subject.vtu: reading crashed (Segmentation fault)"), std::string::npos) << e;
}

TEST(ChildProcess, AHangIsStoppedAtTheTimeLimit) {
  ChildLimits limits;
  limits.seconds = 1;
  const auto start = std::chrono::steady_clock::now();
  const std::string e = error_of(
      []() -> std::vector<char> {
        for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
      },
      limits);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NE(e.find("reading did not finish within 1 s"), std::string::npos) << e;
  EXPECT_LT(seconds, 10);
}

TEST(ChildProcess, AllocationBeyondTheBudgetIsAnErrorNamingTheBudget) {
  ChildLimits limits;
  limits.memory_bytes = size_t{256} << 20;
  const std::string e = error_of(
      [] {
        // Far more than the budget, and than any free heap the child may inherit from earlier tests in this process.
        const std::unique_ptr<char[]> huge(new char[size_t{16} << 30]);
        huge[0] = 1;
        return std::vector<char>(huge.get(), huge.get() + 1);
      },
      limits);
  EXPECT_NE(e.find("reading needs more than 0.2 GB of memory"), std::string::npos) << e;
}

TEST(ChildProcess, TheChildDiesWithItsParent) {
  // A child started by a short-lived process (forked here) is gone once that process is: no such process, or a
  // zombie waiting for whoever adopted it.
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const pid_t middle = ::fork();
  ASSERT_GE(middle, 0);
  if (middle == 0) {
    ::close(fds[0]);
    ChildProcess child = ChildProcess::spawn("s", [](int) {
      for (;;) ::pause();
    });
    char text[32];  // the child's pid, through the pipe; then this process dies without cleaning up
    const int n = std::snprintf(text, sizeof text, "%d", static_cast<int>(child.pid()));
    write_to_parent(fds[1], text, static_cast<size_t>(n));
    ::_exit(0);
  }
  ::close(fds[1]);
  char text[32] = {};
  ASSERT_GT(::read(fds[0], text, sizeof text - 1), 0);
  ::close(fds[0]);
  const pid_t child = static_cast<pid_t>(std::atoi(text));
  int status = 0;
  ::waitpid(middle, &status, 0);
  bool gone = false;
  for (int i = 0; i < 100 && !gone; ++i) {
    std::ifstream stat("/proc/" + std::to_string(child) + "/stat");
    std::string pid, name, state;
    gone = !(stat >> pid >> name >> state) || state == "Z";
    if (!gone) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_TRUE(gone) << "the child " << child << " outlived its parent";
}

}  // namespace
}  // namespace facehex
