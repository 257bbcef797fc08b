#pragma once
// Running out of memory while working on a file, reported as an Error naming the file.
#include <new>
#include <stdexcept>
#include <string>

#include "core/util/error.h"

namespace facehex {

// Runs f() and returns what it returns; running out of memory there (std::bad_alloc, or std::length_error: "cannot
// create std::vector larger than max_size()", what a damaged size asks for) becomes Error(subject, "not enough memory
// to <what>").
template <class F>
auto naming_memory_errors(const std::string& subject, const std::string& what, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const std::bad_alloc&) {
    throw Error(subject, "not enough memory to " + what);
  } catch (const std::length_error& e) {
    throw Error(subject, "not enough memory to " + what + " (" + e.what() + ")");
  }
}

}  // namespace facehex
