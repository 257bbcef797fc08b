#include "core/util/idle_cores.h"

#include <gtest/gtest.h>
#include <sched.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>

namespace facehex {
namespace {

int affinity_cores() {
  cpu_set_t mask;
  EXPECT_EQ(sched_getaffinity(0, sizeof(mask), &mask), 0);
  return CPU_COUNT(&mask);
}

TEST(IdleCores, IsBetweenOneAndTheCoresThisProcessMayUse) {
  const int idle = idle_cores();
  EXPECT_GE(idle, 1);
  EXPECT_LE(idle, affinity_cores());
}

TEST(IdleCores, CountsAnotherProcessThatKeepsACoreBusy) {
  const int cores = affinity_cores();
  if (cores < 2) GTEST_SKIP() << "one core: nothing to take away";
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    for (volatile unsigned long spin = 0;; ++spin) {
    }
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the child is running (or waiting for a core)
  const int idle = idle_cores();
  kill(child, SIGKILL);
  waitpid(child, nullptr, 0);
  EXPECT_LE(idle, cores - 1);
}

}  // namespace
}  // namespace facehex
