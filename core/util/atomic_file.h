#pragma once
// Writing without half-written files: the content goes to a temporary file beside the target, which is renamed
// over the target only once the writer returned without error (rename is atomic on one filesystem).
#include <functional>
#include <string>

namespace facehex {

// Calls write(tmp_path) and renames tmp_path to path. On any exception (or a write that left no file) the temporary
// file is removed and the error is rethrown as facehex::Error naming `path`. Parent folders must exist.
void write_atomically(const std::string& path, const std::function<void(const std::string& tmp_path)>& write);

// Throws facehex::Error(path, ...) unless a file can be written there: its folder exists and is writable, and no
// folder has its name. write_atomically checks it first; commands check their outputs before their work starts.
void check_writable_file(const std::string& path);

}  // namespace facehex
