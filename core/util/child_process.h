#pragma once
// Work in a forked child process, for third-party code that can crash, hang or exhaust memory on bad input (TetGen,
// VTK's readers): whatever it does, the parent gets an answer or a facehex::Error. The child reports through a pipe
// that the parent reads while it runs (compute_in_child's result itself goes through a memory file); it dies with its
// parent (PR_SET_PDEATHSIG), may get an address-space budget on top of what it inherited (RLIMIT_AS) and a wall-time
// limit after which the parent kills it. Linux only, like the rest of the Debian toolchain this builds on. The child
// must not start OpenMP work: GNU OpenMP's threads do not survive a fork.
#include <sys/types.h>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace facehex {

struct ChildLimits {
  double seconds = 0;            // wall time after which the parent kills the child; 0: none
  std::size_t memory_bytes = 0;  // address space the child may add to what it inherited; 0: no limit
};

class ChildProcess {
 public:
  // Starts body(fd) in a child, fd being the write end of the pipe; the child ends with _exit(0) when body returns
  // and with _exit(kThrew) if it throws. Throws Error(subject, ...) if no process can be started.
  static ChildProcess spawn(const std::string& subject, const std::function<void(int fd)>& body,
                            const ChildLimits& limits = {});
  static constexpr int kThrew = 4;

  ChildProcess(ChildProcess&& other) noexcept;
  ChildProcess& operator=(ChildProcess&& other) noexcept;
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess();  // a child still running is killed and reaped

  pid_t pid() const { return pid_; }  // -1 once reaped
  int fd() const { return fd_; }      // the read end, -1 once the child closed it
  // Reads what the child wrote so far (blocks until something comes); false once the pipe is closed.
  bool read_some();
  // Reads until the child closes the pipe; kills it when its time is up (timed_out()).
  void read_all();
  void kill();
  void reap();  // closes the pipe and waits for the child to end

  const std::vector<char>& output() const { return output_; }
  std::vector<char> take_output() { return std::move(output_); }
  bool timed_out() const { return timed_out_; }
  bool crashed() const;             // ended by a signal (after reap())
  std::string signal_name() const;  // of the signal that ended it
  int exit_code() const;            // -1 if it did not exit normally
  const ChildLimits& limits() const { return limits_; }

 private:
  ChildProcess() = default;
  pid_t pid_ = -1;
  int fd_ = -1;
  int status_ = 0;
  bool timed_out_ = false;
  double started_ = 0;  // monotonic seconds
  ChildLimits limits_;
  std::vector<char> output_;
};

// The budget for reading a file in a child: a minute plus two seconds per MB, `base_bytes` plus 64 times the file's
// size (a compressed file may expand that much), generous for any sound file and small beside a damaged one's runaway.
ChildLimits limits_for_reading(const std::string& path, std::size_t base_bytes = std::size_t{2} << 30);

// Writes all bytes to the parent (the pipe, or compute_in_child's memory file), or ends the child if that fails.
void write_to_parent(int fd, const void* data, std::size_t bytes);

// Runs work() in a child and returns its result. A facehex::Error thrown there is thrown here as it was; running
// out of its memory budget, crashing, or running out of time become an Error(subject, ...) that names `what` ("reading
// VTK XML") and the limit.
std::vector<char> compute_in_child(const std::string& subject, const std::string& what,
                                   const std::function<std::vector<char>()>& work, const ChildLimits& limits);

}  // namespace facehex
