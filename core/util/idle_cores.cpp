#include "core/util/idle_cores.h"

#include <sched.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

namespace facehex {
namespace {

// Running threads of the whole machine: the numerator of /proc/loadavg's fourth field ("running/total"); -1 if unread.
int machine_running_threads() {
  std::ifstream in("/proc/loadavg");
  double one, five, fifteen;
  std::string running;
  if (!(in >> one >> five >> fifteen >> running)) return -1;
  try {
    return std::stoi(running.substr(0, running.find('/')));
  } catch (const std::exception&) {
    return -1;
  }
}

// This process's threads in state R (running or runnable), from /proc/self/task/*/stat: the calling thread, and any
// worker still spinning after a parallel step, which must not count as another job's.
int own_running_threads() {
  int running = 0;
  std::error_code error;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", error)) {
    std::ifstream in(task.path() / "stat");
    std::string line;
    if (!std::getline(in, line)) continue;
    const size_t name_end = line.rfind(')');  // the command name may contain spaces and parentheses
    if (name_end != std::string::npos && name_end + 2 < line.size() && line[name_end + 2] == 'R') ++running;
  }
  return std::max(1, running);
}

}  // namespace

int idle_cores() {
  cpu_set_t mask;
  const int cores = sched_getaffinity(0, sizeof(mask), &mask) == 0 ? CPU_COUNT(&mask) : 1;
  const int machine = machine_running_threads();
  if (machine < 0) return std::max(1, cores);
  const int others = std::max(0, machine - own_running_threads());
  return std::clamp(cores - others, 1, std::max(1, cores));
}

}  // namespace facehex
