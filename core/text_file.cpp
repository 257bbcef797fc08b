#include "core/text_file.h"

#include "core/error.h"

#include <cstdio>
#include <fstream>
#include <sstream>

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
  const std::string tmp = path + ".tmp-facehex";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw Error(path, "cannot open file for writing (does the folder exist and is it writable?)");
    out << content;
    out.flush();
    if (!out) {
      std::remove(tmp.c_str());
      throw Error(path, "write failed (disk full?)");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw Error(path, "cannot replace the file");
  }
}

}  // namespace facehex
