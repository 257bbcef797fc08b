#include "core/io/io_util.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>

#include "core/util/error.h"

namespace facehex::io {

namespace fs = std::filesystem;

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::string find_sibling(const std::string& path, const std::string& ext) {
  std::string upper = ext;
  std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return std::toupper(c); });
  for (const std::string& e : {ext, upper}) {
    const std::string candidate = fs::path(path).replace_extension(e).string();
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec)) return candidate;
  }
  return {};
}

void check_readable_file(const std::string& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) throw Error(path, "file not found");
  if (fs::is_directory(status)) throw Error(path, "is a folder, not a mesh file");
  if (!fs::is_regular_file(status)) throw Error(path, "is not a regular file");
  if (fs::file_size(path, ec) == 0) throw Error(path, "file is empty");
  std::ifstream probe(path, std::ios::binary);
  if (!probe) throw Error(path, std::string("cannot open file for reading: ") + std::strerror(errno));
}

std::string format_double(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) fields.push_back(line.substr(start, i - start));
  }
  return fields;
}

// std::from_chars is locale-independent (strtod is not: a German locale would stop at the '.'), but rejects a
// leading '+', which Fortran-style writers (ANSYS) do emit.
static std::string_view strip_plus(std::string_view s) {
  return (s.size() > 1 && s[0] == '+' && s[1] != '-') ? s.substr(1) : s;
}

bool parse_integer(std::string_view s, long* out) {
  s = strip_plus(s);
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), *out);
  return ec == std::errc() && end == s.data() + s.size() && !s.empty();
}

bool parse_real(std::string_view s, double* out) {
  s = strip_plus(s);
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), *out);
  return ec == std::errc() && end == s.data() + s.size() && !s.empty();
}

LineParser::LineParser(const std::string& path, char comment) : path_(path), comment_(comment) {
  check_readable_file(path);
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw Error(path, "read error");
  text_ = ss.str();
}

bool LineParser::next() {
  while (pos_ < text_.size()) {
    size_t end = text_.find('\n', pos_);
    if (end == std::string::npos) end = text_.size();
    std::string_view line(text_.data() + pos_, end - pos_);
    pos_ = end + 1;
    ++line_number_;
    if (line.find('\0') != std::string_view::npos) fail("binary content in a text file");
    if (comment_ != '\0') line = line.substr(0, line.find(comment_));
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.remove_suffix(1);
    fields_ = split_fields(line);
    if (fields_.empty()) continue;
    line_ = line;
    return true;
  }
  line_ = {};
  fields_.clear();
  return false;
}

void LineParser::require_next(const std::string& what) {
  if (!next()) fail("file ends early: expected " + what);
}

void LineParser::require_fields(size_t n, const std::string& what) const {
  if (fields_.size() < n) {
    fail("expected " + std::to_string(n) + " values for " + what + ", found " + std::to_string(fields_.size()));
  }
}

long LineParser::integer(size_t i, const std::string& what) const {
  require_fields(i + 1, what);
  long v = 0;
  if (!parse_integer(fields_[i], &v)) fail("expected an integer " + what + ", found '" + std::string(fields_[i]) + "'");
  return v;
}

double LineParser::real(size_t i, const std::string& what) const {
  require_fields(i + 1, what);
  double v = 0;
  if (!parse_real(fields_[i], &v) || !std::isfinite(v)) {
    fail("expected a finite number for " + what + ", found '" + std::string(fields_[i]) + "'");
  }
  return v;
}

void LineParser::fail(const std::string& problem) const {
  throw Error(path_, problem + ", line " + std::to_string(line_number_));
}

int find_repeated(const int* nodes, int n) {
  for (int k = 1; k < n; ++k)
    for (int j = 0; j < k; ++j)
      if (nodes[j] == nodes[k]) return k;
  return -1;
}

Eigen::MatrixXd rows_to_matrix(const std::vector<double>& values, int cols) {
  if (cols == 0) return Eigen::MatrixXd();
  const Eigen::Index rows = static_cast<Eigen::Index>(values.size()) / cols;
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(values.data(), rows,
                                                                                                  cols);
}

void CellBuilder::add(CellType type, const int* nodes) {
  types_.push_back(type);
  const int n = node_count(type);
  for (int k = 0; k < 8; ++k) nodes_.push_back(k < n ? nodes[k] : -1);
}

void CellBuilder::finish(VolumeMesh* mesh) {
  mesh->C = Eigen::Map<Eigen::Matrix<int, Eigen::Dynamic, 8, Eigen::RowMajor>>(nodes_.data(), size(), 8);
  mesh->types = std::move(types_);
  types_.clear();
  nodes_.clear();
}

void check_volume_mesh(const std::string& subject, const VolumeMesh& mesh) {
  const int nv = mesh.num_vertices();
  const int nc = mesh.num_cells();
  if (nv == 0 || mesh.V.cols() != 3) throw Error(subject, "mesh has no points");
  if (!mesh.V.allFinite()) throw Error(subject, "mesh has non-finite point coordinates");
  if (nc == 0) throw Error(subject, "mesh has no volume cells");
  if (mesh.C.cols() != 8) throw Error(subject, "cell connectivity must have 8 columns");
  if (static_cast<int>(mesh.types.size()) != nc) {
    throw Error(subject, "cell type list (" + std::to_string(mesh.types.size()) + ") and connectivity (" +
                             std::to_string(nc) + " cells) disagree");
  }
  for (int c = 0; c < nc; ++c) {
    const int n = node_count(mesh.types[c]);
    for (int k = 0; k < 8; ++k) {
      const int id = mesh.C(c, k);
      if (k >= n) {
        if (id != -1) throw Error(subject, "cell " + std::to_string(c) + ": unused node slot is not -1");
        continue;
      }
      if (id < 0 || id >= nv) {
        throw Error(subject, "cell " + std::to_string(c) + " refers to point " + std::to_string(id) +
                                 ", but there are " + std::to_string(nv) + " points");
      }
      for (int j = 0; j < k; ++j) {
        if (mesh.C(c, j) == id) {
          throw Error(subject, std::string("cell ") + std::to_string(c) + " (" + cell_type_name(mesh.types[c]) +
                                   ") uses point " + std::to_string(id) + " twice");
        }
      }
    }
  }
  for (const auto& [name, a] : mesh.point_data) {
    if (a.rows() != nv) {
      throw Error(subject, "point data '" + name + "' has " + std::to_string(a.rows()) + " rows for " +
                               std::to_string(nv) + " points");
    }
  }
  for (const auto& [name, a] : mesh.cell_data) {
    if (a.rows() != nc) {
      throw Error(subject, "cell data '" + name + "' has " + std::to_string(a.rows()) + " rows for " +
                               std::to_string(nc) + " cells");
    }
  }
}

// The sizes a VTK XML file declares, checked before VTK's reader trusts them (a count that is negative or past our
// 32-bit indices, or a component count no mesh array has, sends it into a crash or a loop over billions): the XML
// part before the appended data is scanned for every NumberOf... attribute (points, cells, polys, components...).
void check_vtk_xml_sizes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string xml;
  char chunk[1 << 16];
  size_t end = std::string::npos;
  while (end == std::string::npos && in.read(chunk, sizeof chunk).gcount() > 0) {
    xml.append(chunk, static_cast<size_t>(in.gcount()));
    end = xml.find("<AppendedData");
  }
  if (end != std::string::npos) xml.resize(end);
  const std::string key = "NumberOf";
  for (size_t at = xml.find(key); at != std::string::npos; at = xml.find(key, at + 1)) {
    const size_t eq = xml.find("=\"", at);
    if (eq == std::string::npos || eq - at > 40) continue;  // "NumberOf" in text, not an attribute
    const std::string attribute = xml.substr(at, eq - at);
    const size_t from = eq + 2, to = xml.find('"', from);
    const std::string text = xml.substr(from, to == std::string::npos ? 0 : to - from);
    const bool components = attribute == "NumberOfComponents";
    const double least = components ? 1 : 0, most = components ? 1000 : 2147483647.0;
    char* stop = nullptr;
    const double value = std::strtod(text.c_str(), &stop);
    if (text.empty() || *stop != '\0' || !(value >= least && value <= most) || value != std::floor(value))
      throw Error(path, attribute + "=\"" + text + "\" is not a count from " + std::to_string(int(least)) + " to " +
                            std::to_string(static_cast<long long>(most)) + " (a damaged file)");
  }
}

void check_legacy_vtk_cells(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t line = data.find("\nCELLS ");
  if (line == std::string::npos) return;
  const size_t line_end = data.find('\n', line + 1);
  if (line_end == std::string::npos) throw Error(path, "ends in its CELLS line");
  long long n = -1, size = -1;
  char rest = 0;
  if (std::sscanf(data.substr(line + 7, line_end - line - 7).c_str(), "%lld %lld %c", &n, &size, &rest) != 2 || n < 0 ||
      size < 0)
    throw Error(path, "malformed CELLS line (expected CELLS count size)");
  if (data.compare(line_end + 1, 7, "OFFSETS") == 0) return;
  const bool binary = data.find("\nBINARY") != std::string::npos && data.find("\nBINARY") < line;
  // The numbers of the section, no more than `size` of them: a count that runs past them is the damage found.
  std::vector<long long> numbers;
  numbers.reserve(static_cast<size_t>(std::min<long long>(size, static_cast<long long>(data.size()))));
  if (binary) {
    const size_t available = (data.size() - line_end - 1) / 4;
    if (static_cast<unsigned long long>(size) > available)
      throw Error(path, "CELLS declares " + std::to_string(size) + " numbers, the file holds " +
                            std::to_string(available) + " after it");
    for (long long k = 0; k < size; ++k) {
      const auto* b = reinterpret_cast<const unsigned char*>(data.data() + line_end + 1 + 4 * k);
      numbers.push_back(static_cast<std::int32_t>(std::uint32_t{b[0]} << 24 | std::uint32_t{b[1]} << 16 |
                                                  std::uint32_t{b[2]} << 8 | std::uint32_t{b[3]}));
    }
  } else {
    const char* p = data.c_str() + line_end + 1;
    for (long long k = 0; k < size; ++k) {
      char* stop = nullptr;
      errno = 0;
      const long long v = std::strtoll(p, &stop, 10);
      if (stop == p || errno != 0)
        throw Error(path, "CELLS declares " + std::to_string(size) + " numbers, the file holds " + std::to_string(k));
      numbers.push_back(v);
      p = stop;
    }
  }
  long long at = 0;
  for (long long c = 0; c < n; ++c) {
    if (at >= size || numbers[at] < 0 || numbers[at] >= size - at)
      throw Error(path, "cell " + std::to_string(c + 1) + " of " + std::to_string(n) +
                            " runs past the CELLS section's declared " + std::to_string(size) + " numbers");
    at += 1 + numbers[at];
  }
  if (at != size)
    throw Error(path, "the CELLS section's " + std::to_string(n) + " cells hold " + std::to_string(at) +
                          " numbers, it declares " + std::to_string(size));
}

}  // namespace facehex::io
