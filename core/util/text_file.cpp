#include "core/util/text_file.h"

#include <fstream>
#include <sstream>

#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace facehex {

std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open file for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw Error(path, "read error");
  return ss.str();
}

void write_text_file(const std::string& path, const std::string& content) {
  write_atomically(path, [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw Error(tmp, "cannot open file for writing");
    out << content;
    out.flush();
    if (!out) throw Error(tmp, "write failed (disk full?)");
  });
}

}  // namespace facehex
