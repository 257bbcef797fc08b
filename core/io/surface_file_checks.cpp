#include "core/io/surface_file_checks.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>
#include <vector>

#include "core/io/io_util.h"
#include "core/util/error.h"

namespace facehex::io {

namespace {

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Unsigned little-endian integer of `size` bytes at p.
uint64_t little_endian(const unsigned char* p, int size) {
  uint64_t v = 0;
  for (int i = size - 1; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

// ---- PLY ----

struct PlyProperty {
  int size = 0;        // bytes of a scalar, or of a list item
  int count_size = 0;  // bytes of a list's count; 0 for scalars
  bool is_signed = false, is_float = false;
  bool is_vertex_index = false;  // the face list that refers to vertices
};

struct PlyElement {
  std::string name;
  long count = 0;
  std::vector<PlyProperty> properties;
};

int ply_type_size(std::string_view t, bool* is_signed, bool* is_float) {
  *is_signed = !(t[0] == 'u');
  *is_float = t.rfind("float", 0) == 0 || t == "double";
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

class PlyChecker {
 public:
  explicit PlyChecker(const std::string& path) : path_(path), data_(read_all(path)) {}

  void check() {
    const size_t body = parse_header();
    if (format_ == "ascii") {
      check_ascii(body);
    } else {
      check_binary(body, format_ == "binary_big_endian");
    }
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const { throw Error(path_, "PLY file " + problem); }

  // Returns the offset of the body.
  size_t parse_header() {
    if (data_.compare(0, 4, "ply\n") != 0 && data_.compare(0, 5, "ply\r\n") != 0) fail("does not start with 'ply'");
    size_t pos = 0;
    int line_number = 0;
    while (true) {
      const size_t end = data_.find('\n', pos);
      if (end == std::string::npos) fail("header has no end_header line");
      const std::string_view line(data_.data() + pos, end - pos);
      pos = end + 1;
      ++line_number;
      const std::vector<std::string_view> f = split_fields(line);
      auto bad = [&](const std::string& why) { fail("header: " + why + ", line " + std::to_string(line_number)); };
      if (f.empty() || f[0] == "comment" || f[0] == "obj_info" || f[0] == "ply") continue;
      if (f[0] == "end_header") return pos;
      if (f[0] == "format") {
        if (f.size() < 2 || (f[1] != "ascii" && f[1] != "binary_little_endian" && f[1] != "binary_big_endian")) {
          bad("unknown format");
        }
        format_ = std::string(f[1]);
      } else if (f[0] == "element") {
        long count = 0;
        if (f.size() != 3 || !parse_integer(f[2], &count) || count < 0) bad("expected 'element <name> <count>'");
        elements_.push_back({std::string(f[1]), count, {}});
      } else if (f[0] == "property") {
        if (elements_.empty()) bad("property before any element");
        PlyProperty p;
        bool count_signed = false, count_float = false;
        if (f.size() == 5 && f[1] == "list") {
          p.count_size = ply_type_size(f[2], &count_signed, &count_float);
          p.size = ply_type_size(f[3], &p.is_signed, &p.is_float);
          if (p.count_size == 0 || count_float || p.size == 0) bad("unknown list property types");
          p.is_vertex_index = elements_.back().name == "face" && (f[4] == "vertex_indices" || f[4] == "vertex_index");
        } else if (f.size() == 3) {
          p.size = ply_type_size(f[1], &p.is_signed, &p.is_float);
          if (p.size == 0) bad("unknown property type '" + std::string(f[1]) + "'");
        } else {
          bad("malformed property");
        }
        elements_.back().properties.push_back(p);
      } else {
        bad("unknown keyword '" + std::string(f[0]) + "'");
      }
    }
  }

  long vertex_count() const {
    for (const PlyElement& e : elements_)
      if (e.name == "vertex") return e.count;
    return 0;
  }

  [[noreturn]] void ends_early(const PlyElement& e, long i) const {
    fail("is truncated: it ends in element '" + e.name + "' " + std::to_string(i + 1) + " of " +
         std::to_string(e.count));
  }

  void check_index(const PlyElement& e, long i, double index) const {
    if (index < 0 || index >= vertex_count()) {
      fail("face " + std::to_string(i + 1) + " of " + std::to_string(e.count) + " refers to vertex " +
           std::to_string(static_cast<long long>(index)) + " of " + std::to_string(vertex_count()));
    }
  }

  void check_ascii(size_t body) const {
    const std::vector<std::string_view> tokens = split_fields(std::string_view(data_).substr(body));
    size_t t = 0;
    auto number = [&](const PlyElement& e, long i) {
      double v = 0;
      if (t >= tokens.size()) ends_early(e, i);
      if (!parse_real(tokens[t], &v)) fail("has '" + std::string(tokens[t]) + "' where a number belongs");
      ++t;
      return v;
    };
    for (const PlyElement& e : elements_) {
      for (long i = 0; i < e.count; ++i) {
        for (const PlyProperty& p : e.properties) {
          if (p.count_size == 0) {
            number(e, i);
            continue;
          }
          const double n = number(e, i);
          if (n < 0) fail("has a negative list length");
          for (long k = 0; k < static_cast<long>(n); ++k) {
            const double v = number(e, i);
            if (p.is_vertex_index) check_index(e, i, v);
          }
        }
      }
    }
    // VTK's reader takes the data line by line and frees a buffer twice when the last line has no end.
    if (t > 0) {
      const size_t last_end = static_cast<size_t>(tokens[t - 1].data() + tokens[t - 1].size() - data_.data());
      if (data_.find('\n', last_end) == std::string::npos) fail("ends without a line end after its last element");
    }
  }

  void check_binary(size_t body, bool big_endian) const {
    const auto* bytes = reinterpret_cast<const unsigned char*>(data_.data());
    size_t pos = body;
    auto read_int = [&](const PlyElement& e, long i, int size, bool is_signed) -> int64_t {
      if (pos + size > data_.size()) ends_early(e, i);
      unsigned char buf[8];
      std::memcpy(buf, bytes + pos, size);
      if (big_endian) std::reverse(buf, buf + size);
      pos += size;
      const uint64_t u = little_endian(buf, size);
      if (!is_signed || size == 8) return static_cast<int64_t>(u);
      const uint64_t sign = uint64_t{1} << (8 * size - 1);
      return static_cast<int64_t>(u ^ sign) - static_cast<int64_t>(sign);
    };
    for (const PlyElement& e : elements_) {
      for (long i = 0; i < e.count; ++i) {
        for (const PlyProperty& p : e.properties) {
          if (p.count_size == 0) {
            if (pos + p.size > data_.size()) ends_early(e, i);
            pos += p.size;
            continue;
          }
          const int64_t n = read_int(e, i, p.count_size, false);
          if (!p.is_vertex_index || p.is_float) {
            if (pos + n * p.size > data_.size()) ends_early(e, i);
            pos += n * p.size;
            continue;
          }
          for (int64_t k = 0; k < n; ++k) check_index(e, i, static_cast<double>(read_int(e, i, p.size, p.is_signed)));
        }
      }
    }
  }

  std::string path_;
  std::string data_;
  std::string format_;
  std::vector<PlyElement> elements_;
};

}  // namespace

void check_stl_file(const std::string& path) {
  const std::string data = read_all(path);
  const uint64_t size = data.size();
  const uint64_t announced =
      size >= 84 ? little_endian(reinterpret_cast<const unsigned char*>(data.data()) + 80, 4) : 0;
  // ASCII starts with "solid"; so do some binary headers, but then the size matches the count.
  if (data.compare(0, 5, "solid") == 0 && size != 84 + 50 * announced) return;
  if (size < 84 || (size - 84) % 50 != 0 || size < 84 + 50 * announced) {
    throw Error(path, "binary STL is truncated: its header announces " + std::to_string(announced) + " triangles (" +
                          std::to_string(84 + 50 * announced) + " bytes), the file has " + std::to_string(size) +
                          " bytes");
  }
}

void check_ply_file(const std::string& path) { PlyChecker(path).check(); }

void check_obj_file(const std::string& path) {
  // Two passes: faces may (rarely) come before the vertices they use.
  long vertices = 0;
  for (LineParser in(path, '#'); in.next();) {
    if (in.field(0) != "v") continue;
    in.require_fields(4, "a vertex (v x y z)");
    for (int k = 1; k <= 3; ++k) in.real(k, "a vertex coordinate");
    ++vertices;
  }
  for (LineParser in(path, '#'); in.next();) {
    if (in.field(0) != "f") continue;
    in.require_fields(4, "a face (f and at least 3 vertices)");
    for (size_t k = 1; k < in.size(); ++k) {
      const std::string_view ref = in.field(k);
      long index = 0;
      if (!parse_integer(ref.substr(0, ref.find('/')), &index)) {
        in.fail("malformed face vertex '" + std::string(ref) + "'");
      }
      // 1-based, or negative: relative to the end of the list.
      if (index == 0 || index > vertices || -index > vertices) {
        in.fail("face refers to vertex " + std::to_string(index) + ", but there are " + std::to_string(vertices));
      }
    }
  }
}

}  // namespace facehex::io
