#pragma once
// Whole-file text I/O with facehex::Error messages naming the file. Writes are atomic (temporary file + rename), so
// an interrupted or failed write never leaves a partial file.
#include <string>

namespace facehex {

std::string read_text_file(const std::string& path);
void write_text_file(const std::string& path, const std::string& content);

}  // namespace facehex
