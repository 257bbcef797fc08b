#pragma once
// Helpers shared by the mesh readers and writers of core/io (not part of the public API): file-name handling,
// up-front file checks, a line-by-line text parser whose errors carry "line N", number formatting that
// round-trips, and the consistency checks every reader runs before it hands out a mesh.
#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "core/mesh/mesh.h"

namespace facehex::io {

// ".vtu" for "dir/Mesh.VTU"; empty when the name has no extension.
std::string lower_extension(const std::string& path);

// The file beside `path` with its extension replaced by `ext` (".ele"), trying `ext` as given, then upper case;
// empty when neither exists.
std::string find_sibling(const std::string& path, const std::string& ext);

// Throws facehex::Error(path, ...) unless path names an existing, non-empty, readable regular file. Readers call
// it first so that "file not found" is not reported as some parser's confusion.
void check_readable_file(const std::string& path);
// A VTK XML file's declared sizes (every NumberOf... attribute before its appended data) are counts our readers can
// hold: 0 .. 2^31-1, components 1 .. 1000. Throws Error(path, ...) naming the attribute.
void check_vtk_xml_sizes(const std::string& path);
// A legacy VTK file's CELLS section before format 5.1 ("CELLS n size", then n rows "count id..."; ASCII or big-endian
// binary int32) holds exactly `size` numbers and its rows' counts add up to them: VTK's reader walks the rows by their
// counts through a buffer of `size` and runs past its end when they need more. Throws Error(path, ...). Files of
// format 5.1 (OFFSETS and CONNECTIVITY) and files without CELLS pass.
void check_legacy_vtk_cells(const std::string& path);

// Text that reads back to exactly the same double (%.17g).
std::string format_double(double x);

// Reads a whole text file and hands it out one line at a time, split into whitespace-separated fields. Blank
// lines and (if a comment character is set) comments are skipped. Every parse error is a facehex::Error naming the
// file and ending in ", line N".
class LineParser {
 public:
  explicit LineParser(const std::string& path, char comment = '\0');

  // Moves to the next non-blank line; false at the end of the file.
  bool next();
  // As next(), but a missing line is an error: "file ends early: expected <what>".
  void require_next(const std::string& what);

  const std::string& path() const { return path_; }
  int line_number() const { return line_number_; }
  std::string_view line() const { return line_; }  // without comment, line ending
  size_t size() const { return fields_.size(); }
  std::string_view field(size_t i) const { return fields_.at(i); }

  // Fails unless the line has at least n fields ("expected n values for <what>, found m").
  void require_fields(size_t n, const std::string& what) const;
  long integer(size_t i, const std::string& what) const;
  double real(size_t i, const std::string& what) const;  // finite only

  [[noreturn]] void fail(const std::string& problem) const;

 private:
  std::string path_;
  std::string text_;
  size_t pos_ = 0;
  char comment_;
  int line_number_ = 0;
  std::string_view line_;
  std::vector<std::string_view> fields_;
};

std::vector<std::string_view> split_fields(std::string_view line);
// Strict conversions of a whole field (no trailing junk, leading '+' allowed); false when not a number.
bool parse_integer(std::string_view s, long* out);
bool parse_real(std::string_view s, double* out);

// Position of the first node that repeats an earlier one in nodes[0..n), or -1: readers report degenerate cells
// in the file's own terms before check_volume_mesh would in 0-based ones.
int find_repeated(const int* nodes, int n);

// Row-major values (cols per row) as a #rows x cols matrix. Readers collect into vectors and convert at the end, so
// that a garbage header announcing 10^9 records cannot make them allocate gigabytes up front.
Eigen::MatrixXd rows_to_matrix(const std::vector<double>& values, int cols);

// Collects cells in VTK order while a reader parses, then builds the VolumeMesh. Keeping the conversion to the
// #C x 8 layout in one place means every reader pads unused slots with -1 the same way.
class CellBuilder {
 public:
  void add(CellType type, const int* nodes);
  int size() const { return static_cast<int>(types_.size()); }
  // Moves the collected cells into mesh.C / mesh.types.
  void finish(VolumeMesh* mesh);

 private:
  std::vector<CellType> types_;
  std::vector<int> nodes_;  // 8 per cell
};

// Throws facehex::Error(subject, ...) unless the mesh is self-consistent: #V x 3 finite points, at least one cell,
// #C x 8 connectivity with valid node ids for each cell's type (-1 in unused slots), no repeated node in a cell,
// data arrays with #V / #C rows. Readers call it before returning, writers before writing anything.
void check_volume_mesh(const std::string& subject, const VolumeMesh& mesh);

}  // namespace facehex::io
