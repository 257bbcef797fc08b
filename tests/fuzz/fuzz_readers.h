#pragma once
// The readers the fuzz targets exercise (tests/fuzz/CMakeLists.txt, docs/robustness.md) and the regression test of
// what they found. An input is written to the file(s) a reader takes and read through the product's own entry
// point, so that what is fuzzed is what a user's file meets: our checks and parsers in this process, VTK's readers in
// the child process the product forks for them.
//
// One input can stand for several files: its parts are separated by kFileSeparator (a TetGen .node and .ele, a
// MetaImage .mhd and its .raw). A reader that takes several formats (surfaces: .stl, .obj, .ply, .vtp) spends the
// input's first byte choosing one.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace facehex::fuzz {

constexpr std::string_view kFileSeparator = "\n--facehex-fuzz-next-file--\n";

const std::vector<std::string>& reader_names();  // "vtu", "vtk", "msh", ...

// Writes the input's files into the folder `dir` (its entries are removed first) and reads them with reader `reader`.
// Returns the message of the facehex::Error that refused the input, nothing when it was read. Any other exception
// propagates, as a crash does: both are findings.
std::optional<std::string> read_input(const std::string& reader, const std::uint8_t* data, std::size_t size,
                                      const std::string& dir);

// The file read_input hands to the reader for this input (a refusal must name it).
std::string input_path(const std::string& reader, const std::uint8_t* data, std::size_t size, const std::string& dir);

}  // namespace facehex::fuzz
