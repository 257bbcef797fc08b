#pragma once
// How many of the cores this process may run on are idle now.
//
// A stage made of many short parallel steps (the untangler's sweeps) waits at the end of each step for its slowest
// thread. With more threads than idle cores, one of them is often waiting for a core, and the stage runs several
// times slower than it would on one thread; such stages size their thread teams with this.

namespace facehex {

// The cores in this process's affinity mask minus the threads of other processes running at this instant
// (/proc/loadavg's running count, less this process's own running threads), at least 1. Without /proc: every core.
int idle_cores();

}  // namespace facehex
