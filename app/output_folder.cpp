#include "app/output_folder.h"

#include <openssl/evp.h>
#include <unistd.h>

#include <fstream>
#include <iomanip>
#include <sstream>

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

namespace {

std::string sha256_of_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string(), "cannot be read back for its checksum");
  EVP_MD_CTX* context = EVP_MD_CTX_new();
  EVP_DigestInit_ex(context, EVP_sha256(), nullptr);
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk).gcount() > 0) EVP_DigestUpdate(context, chunk, static_cast<size_t>(in.gcount()));
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  EVP_DigestFinal_ex(context, digest, &size);
  EVP_MD_CTX_free(context);
  std::ostringstream hex;
  for (unsigned int i = 0; i < size; ++i) hex << std::hex << std::setw(2) << std::setfill('0') << int(digest[i]);
  return hex.str();
}

}  // namespace

std::vector<std::string> OutputFolder::remove_stale(const std::vector<std::string>& names) const {
  std::vector<std::string> removed;
  for (const std::string& name : names) {
    std::error_code ec;
    if (fs::remove(folder_ / name, ec)) removed.push_back(name);
    if (ec) throw Error((folder_ / name).string(), "an earlier output cannot be removed: " + ec.message());
  }
  return removed;
}

nlohmann::json OutputFolder::completion_record(const std::vector<std::string>& names) const {
  nlohmann::json files = nlohmann::json::array();
  for (const std::string& name : names)
    files.push_back(
        {{"name", name}, {"bytes", fs::file_size(folder_ / name)}, {"sha256", sha256_of_file(folder_ / name)}});
  return {{"complete", true}, {"files", files}};
}

OutputFolder::~OutputFolder() {
  if (created_.empty()) return;
  std::error_code ignored;  // a destructor must not throw; the command's own error is what the user needs to see
  fs::remove_all(created_, ignored);
}

}  // namespace facehex::cli
