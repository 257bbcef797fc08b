#pragma once
// Messages of the JSON library's exceptions for the user: "[json.exception.type_error.302] type must be number, but
// is string" without its error code.
#include <string>

namespace facehex {

inline std::string without_json_error_code(const std::string& what) {
  const size_t code_end = what.find("] ");
  return what.rfind("[json.exception.", 0) == 0 && code_end != std::string::npos ? what.substr(code_end + 2) : what;
}

}  // namespace facehex
