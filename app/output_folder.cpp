#include "app/output_folder.h"

#include <unistd.h>

#include "core/util/error.h"

namespace fs = std::filesystem;

namespace facehex::cli {

OutputFolder::OutputFolder(const fs::path& folder) : folder_(folder) {
  // The outermost missing ancestor is what a failure has to remove.
  std::error_code ec;
  for (fs::path p = fs::absolute(folder, ec).lexically_normal(); !p.empty() && !fs::exists(p, ec);
       p = p.parent_path()) {
    created_ = p;
    if (p == p.parent_path()) break;
  }
  fs::create_directories(folder_, ec);
  if (ec || !fs::is_directory(folder_)) {
    created_.clear();
    throw Error(folder_.string(), "cannot create the output folder" + (ec ? ": " + ec.message() : std::string()));
  }
  if (::access(folder_.c_str(), W_OK | X_OK) != 0) {
    std::error_code ignored;
    if (!created_.empty()) fs::remove_all(created_, ignored);
    created_.clear();
    throw Error(folder_.string(), "the output folder is not writable");
  }
}

OutputFolder::~OutputFolder() {
  if (created_.empty()) return;
  std::error_code ignored;  // a destructor must not throw; the command's own error is what the user needs to see
  fs::remove_all(created_, ignored);
}

}  // namespace facehex::cli
