#include "core/util/child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <new>

#include "core/util/error.h"

namespace facehex {
namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// The child's present address-space size, from /proc/self/statm (in pages).
std::size_t address_space_bytes() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  unsigned long pages = 0;
  if (f) {
    if (std::fscanf(f, "%lu", &pages) != 1) pages = 0;
    std::fclose(f);
  }
  return static_cast<std::size_t>(pages) * static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
}

[[noreturn]] void run_child(int fd, pid_t parent, const std::function<void(int)>& body, const ChildLimits& limits) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(3);  // the parent died before the line above
  if (limits.memory_bytes > 0) {
    const rlim_t cap = static_cast<rlim_t>(address_space_bytes() + limits.memory_bytes);
    const rlimit limit{cap, cap};
    ::setrlimit(RLIMIT_AS, &limit);
  }
  try {
    body(fd);
  } catch (...) {
    ::_exit(ChildProcess::kThrew);
  }
  ::_exit(0);
}

// compute_in_child's message: a kind, then the result or the error's subject and problem.
enum Kind : std::uint8_t { kResult = 0, kError = 1, kOutOfMemory = 2 };

// The kind and a size, then the payload (an error's text); a result's size is that of the memory file holding it.
void send(int fd, Kind kind, const std::vector<char>& payload, std::uint64_t size) {
  write_to_parent(fd, &kind, sizeof kind);
  write_to_parent(fd, &size, sizeof size);
  if (!payload.empty()) write_to_parent(fd, payload.data(), payload.size());
}

void send(int fd, Kind kind, const std::vector<char>& payload) { send(fd, kind, payload, payload.size()); }

std::vector<char> error_payload(const std::string& subject, const std::string& problem) {
  std::vector<char> p(subject.begin(), subject.end());
  p.push_back('\0');
  p.insert(p.end(), problem.begin(), problem.end());
  return p;
}

std::string gigabytes(std::size_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f GB", static_cast<double>(bytes) / (1 << 30));
  return text;
}

}  // namespace

ChildProcess ChildProcess::spawn(const std::string& subject, const std::function<void(int)>& body,
                                 const ChildLimits& limits) {
  int fds[2];
  if (::pipe(fds) != 0) throw Error(subject, std::string("cannot create a pipe: ") + std::strerror(errno));
  const pid_t parent = ::getpid();
  ChildProcess child;
  child.limits_ = limits;
  child.started_ = now();
  child.pid_ = ::fork();
  if (child.pid_ < 0) {
    ::close(fds[0]), ::close(fds[1]);
    throw Error(subject, std::string("cannot start a process: ") + std::strerror(errno));
  }
  if (child.pid_ == 0) {
    ::close(fds[0]);
    run_child(fds[1], parent, body, limits);
  }
  ::close(fds[1]);
  child.fd_ = fds[0];
  return child;
}

ChildProcess::ChildProcess(ChildProcess&& o) noexcept { *this = std::move(o); }

ChildProcess& ChildProcess::operator=(ChildProcess&& o) noexcept {
  std::swap(pid_, o.pid_);
  std::swap(fd_, o.fd_);
  std::swap(status_, o.status_);
  std::swap(timed_out_, o.timed_out_);
  std::swap(started_, o.started_);
  std::swap(limits_, o.limits_);
  std::swap(output_, o.output_);
  return *this;
}

ChildProcess::~ChildProcess() {
  if (pid_ > 0) {
    kill();
    reap();
  }
}

bool ChildProcess::read_some() {
  if (fd_ < 0) return false;
  char chunk[1 << 16];
  const ssize_t n = ::read(fd_, chunk, sizeof chunk);
  if (n < 0 && errno == EINTR) return true;
  if (n <= 0) {
    ::close(fd_);
    fd_ = -1;
    return false;
  }
  output_.insert(output_.end(), chunk, chunk + n);
  return true;
}

void ChildProcess::read_all() {
  while (fd_ >= 0) {
    int wait_ms = -1;
    if (limits_.seconds > 0) {
      const double left = started_ + limits_.seconds - now();
      if (left <= 0) {
        timed_out_ = true;
        kill();
        ::close(fd_);
        fd_ = -1;
        return;
      }
      wait_ms = static_cast<int>(std::ceil(left * 1000));
    }
    pollfd watch{fd_, POLLIN, 0};
    const int ready = ::poll(&watch, 1, wait_ms);
    if (ready < 0 && errno != EINTR) {
      kill();
      ::close(fd_);
      fd_ = -1;
      return;
    }
    if (ready > 0) read_some();
  }
}

void ChildProcess::kill() {
  if (pid_ > 0) ::kill(pid_, SIGKILL);
}

void ChildProcess::reap() {
  if (fd_ >= 0) ::close(fd_), fd_ = -1;
  if (pid_ <= 0) return;
  while (::waitpid(pid_, &status_, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
}

bool ChildProcess::crashed() const { return WIFSIGNALED(status_); }

std::string ChildProcess::signal_name() const { return crashed() ? strsignal(WTERMSIG(status_)) : ""; }

int ChildProcess::exit_code() const { return WIFEXITED(status_) ? WEXITSTATUS(status_) : -1; }

ChildLimits limits_for_reading(const std::string& path, std::size_t base_bytes) {
  std::error_code ec;
  const double megabytes = static_cast<double>(std::filesystem::file_size(path, ec)) / (1 << 20);
  ChildLimits limits;
  limits.seconds = 60 + 2 * (ec ? 0 : megabytes);
  limits.memory_bytes = base_bytes + static_cast<std::size_t>(64 * (ec ? 0 : megabytes)) * (std::size_t{1} << 20);
  return limits;
}

void write_to_parent(int fd, const void* data, std::size_t bytes) {
  const char* p = static_cast<const char*>(data);
  while (bytes > 0) {
    const ssize_t n = ::write(fd, p, bytes);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) ::_exit(3);  // the parent is gone, or the memory file cannot grow: it sees no result
    p += n, bytes -= static_cast<std::size_t>(n);
  }
}

std::vector<char> compute_in_child(const std::string& subject, const std::string& what,
                                   const std::function<std::vector<char>()>& work, const ChildLimits& limits) {
  // The result goes through a memory file rather than the pipe: a CT volume is hundreds of MB, which a pipe would
  // carry 64 KB at a time, switching between the two processes for each piece.
  const int result_file = ::memfd_create("facehex-child-result", MFD_CLOEXEC);
  if (result_file < 0) throw Error(subject, std::string("cannot create a memory file: ") + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{result_file};
  ChildProcess child = ChildProcess::spawn(
      subject,
      [&](int fd) {
        // Third-party chatter (MetaIO prints its complaints to stderr) would come before the one-line error the
        // parent reports: the child's result and error go through the pipe only.
        const int devnull = ::open("/dev/null", O_WRONLY);
        if (devnull >= 0) ::dup2(devnull, STDOUT_FILENO), ::dup2(devnull, STDERR_FILENO);
        try {
          const std::vector<char> result = work();
          write_to_parent(result_file, result.data(), result.size());
          send(fd, kResult, {}, result.size());
        } catch (const Error& e) {
          const std::string message = e.what();
          const std::string prefix = e.subject().empty() ? "" : e.subject() + ": ";
          send(fd, kError, error_payload(e.subject(), message.substr(prefix.size())));
        } catch (const std::bad_alloc&) {
          send(fd, kOutOfMemory, {});
        } catch (const std::length_error&) {  // "cannot create std::vector larger than max_size()"
          send(fd, kOutOfMemory, {});
        } catch (const std::exception& e) {
          send(fd, kError, error_payload(subject, what + " failed: " + e.what()));
        }
      },
      limits);
  child.read_all();
  child.reap();
  if (child.timed_out())
    throw Error(subject, what + " did not finish within " + std::to_string(static_cast<int>(limits.seconds)) +
                             " s (a damaged file?); stopped");
  if (child.crashed())
    throw Error(subject, what + " crashed (" + child.signal_name() + "): the file is damaged or not what it claims");
  std::vector<char> message = child.take_output();
  std::uint8_t kind = 0;
  std::uint64_t size = 0;
  const std::size_t header = sizeof kind + sizeof size;
  if (child.exit_code() != 0 || message.size() < header)
    throw Error(subject, what + " ended without a result (exit code " + std::to_string(child.exit_code()) + ")");
  std::memcpy(&kind, message.data(), sizeof kind);
  std::memcpy(&size, message.data() + sizeof kind, sizeof size);
  if (kind == kOutOfMemory)
    throw Error(subject, what + " needs more than " + gigabytes(limits.memory_bytes) +
                             " of memory (a damaged file, or sizes it does not hold?)");
  if (kind == kError) {
    if (message.size() != header + size) throw Error(subject, what + " sent an incomplete result");
    const auto nul = std::find(message.begin() + header, message.end(), '\0');
    const std::string error_subject(message.begin() + header, nul);
    const std::string problem(nul == message.end() ? nul : nul + 1, message.end());
    throw Error(error_subject, problem);
  }
  struct stat file {};
  if (message.size() != header || ::fstat(result_file, &file) != 0 || static_cast<std::uint64_t>(file.st_size) != size)
    throw Error(subject, what + " sent an incomplete result");
  std::vector<char> result(size);
  for (std::size_t at = 0; at < size;) {
    const ssize_t n = ::pread(result_file, result.data() + at, size - at, static_cast<off_t>(at));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw Error(subject, what + " sent an incomplete result");
    at += static_cast<std::size_t>(n);
  }
  return result;
}

}  // namespace facehex
