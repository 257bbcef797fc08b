#pragma once
// The output folder of a command: created (with missing parents) and checked for writing before the long work
// starts, so a bad -o fails in a second; removed again if the command fails before keep(), so a failed run leaves
// no empty or half-filled folder behind. A folder that existed before is never removed (each file in it is written
// atomically, core/atomic_file.h).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

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

  // Removes the files of these names that an earlier command left here and this one will not write again (an
  // export format not asked for this time), so that the folder holds one run's outputs only. Returns the removed.
  std::vector<std::string> remove_stale(const std::vector<std::string>& names) const;
  // What a finished command wrote, for its report (written last): {"complete": true, "files": [{"name", "bytes",
  // "sha256"}]}; a folder whose report lacks it, or whose files do not match it, is not a finished run's.
  nlohmann::json completion_record(const std::vector<std::string>& names) const;

 private:
  std::filesystem::path folder_;
  std::filesystem::path created_;  // the outermost folder this object created (empty: none, or kept)
};

}  // namespace facehex::cli
