#pragma once
// The output folder of a command: created (with missing parents) and checked for writing before the long work
// starts, so a bad -o fails in a second; removed again if the command fails before keep(), so a failed run leaves
// no empty or half-filled folder behind. A folder that existed before is never removed (each file in it is written
// atomically, core/atomic_file.h).
#include <filesystem>
#include <string>

namespace facehex::cli {

class OutputFolder {
 public:
  // Throws facehex::Error naming the folder when it cannot be created or written to.
  explicit OutputFolder(const std::filesystem::path& folder);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  std::filesystem::path file(const std::string& name) const { return folder_ / name; }
  const std::filesystem::path& path() const { return folder_; }
  // The command succeeded: the folder stays.
  void keep() { created_.clear(); }

 private:
  std::filesystem::path folder_;
  std::filesystem::path created_;  // the outermost folder this object created (empty: none, or kept)
};

}  // namespace facehex::cli
