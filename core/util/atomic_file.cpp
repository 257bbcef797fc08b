#include "core/util/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <random>

#include "core/util/error.h"

namespace facehex {

namespace fs = std::filesystem;

namespace {

// The folder the file goes into must exist and be writable: checked first so that the message says so plainly
// instead of "cannot open .mesh.vtu.tmpa8Zq1c".
fs::path checked_parent(const std::string& path) {
  if (path.empty()) throw Error("write", "no output file name given");
  fs::path parent = fs::path(path).parent_path();
  if (parent.empty()) parent = ".";
  std::error_code ec;
  const fs::file_status status = fs::status(parent, ec);
  if (!fs::exists(status)) throw Error(path, "cannot write: folder '" + parent.string() + "' does not exist");
  if (!fs::is_directory(status)) throw Error(path, "cannot write: '" + parent.string() + "' is not a folder");
  if (::access(parent.c_str(), W_OK | X_OK) != 0) {
    throw Error(path, "cannot write: folder '" + parent.string() + "' is not writable");
  }
  if (fs::is_directory(fs::status(path, ec))) throw Error(path, "cannot write: a folder of that name exists");
  return parent;
}

// A name nobody else uses, ".mesh.tmpXXXXXX.vtu" for "mesh.vtu": hidden (leading '.') so that half-written files do
// not show up in file dialogs; in the same folder so that the final rename stays on one filesystem (and therefore
// atomic); with the target's extension because some writers insist on it (vtkPLYWriter appends ".ply" otherwise).
// The writer creates the file itself, so it gets the usual permissions (mkstemp would make it 0600).
std::string temp_name(const fs::path& parent, const std::string& path) {
  static const char kChars[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  static thread_local std::mt19937_64 rng(std::random_device{}() ^ (static_cast<uint64_t>(::getpid()) << 32));
  const fs::path name = fs::path(path).filename();
  for (int attempt = 0; attempt < 100; ++attempt) {
    std::string random;
    for (int i = 0; i < 6; ++i) random += kChars[rng() % (sizeof kChars - 1)];
    const std::string name_tmp = "." + name.stem().string() + ".tmp" + random + name.extension().string();
    const fs::path candidate = parent / name_tmp;
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(candidate, ec))) return candidate.string();
  }
  throw Error(path, "cannot find a free temporary file name");
}

// Flushes the new content to disk before the rename, so that a crash right after cannot leave an empty target.
void sync_file(const std::string& tmp) {
  const int fd = ::open(tmp.c_str(), O_RDONLY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

// Messages from the writer may name the temporary file; the user only knows the target.
std::string mention_target(std::string message, const std::string& tmp, const std::string& path) {
  for (size_t at = message.find(tmp); at != std::string::npos; at = message.find(tmp, at + path.size())) {
    message.replace(at, tmp.size(), path);
  }
  return message;
}

}  // namespace

void check_writable_file(const std::string& path) { checked_parent(path); }

void write_atomically(const std::string& path, const std::function<void(const std::string& tmp_path)>& write) {
  const fs::path parent = checked_parent(path);
  const std::string tmp = temp_name(parent, path);
  auto discard = [&tmp] {
    std::error_code ec;
    fs::remove(tmp, ec);
  };
  try {
    write(tmp);
  } catch (const Error& e) {
    discard();
    if (e.subject() == path) throw;
    throw Error(
        path, mention_target(e.subject() == tmp ? std::string(e.what()).substr(tmp.size() + 2) : e.what(), tmp, path));
  } catch (const std::exception& e) {
    discard();
    throw Error(path, mention_target(e.what(), tmp, path));
  } catch (...) {
    discard();
    throw Error(path, "unknown error while writing");
  }
  std::error_code ec;
  if (!fs::is_regular_file(tmp, ec)) {
    discard();
    throw Error(path, "writing failed: no file was produced");
  }
  sync_file(tmp);
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    discard();
    throw Error(path, "cannot replace the file: " + reason);
  }
}

}  // namespace facehex
