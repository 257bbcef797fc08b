#include "core/segment/metaimage_header.h"

#include <zlib.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/util/error.h"

namespace facehex {
namespace {

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

std::vector<double> numbers(const std::string& path, const std::string& key, const std::string& text, size_t count) {
  std::istringstream in(text);
  std::vector<double> v;
  double x;
  while (in >> x) v.push_back(x);
  if (v.size() != count || !in.eof())
    throw Error(path, key + " must hold " + std::to_string(count) + " numbers, got '" + text + "'");
  for (double y : v)
    if (!std::isfinite(y)) throw Error(path, key + " holds a value that is not a finite number: '" + text + "'");
  return v;
}

long long element_bytes(const std::string& path, const std::string& type) {
  static const std::map<std::string, long long> sizes = {{"MET_CHAR", 1},       {"MET_UCHAR", 1}, {"MET_SHORT", 2},
                                                         {"MET_USHORT", 2},     {"MET_INT", 4},   {"MET_UINT", 4},
                                                         {"MET_LONG", 4},       {"MET_ULONG", 4}, {"MET_LONG_LONG", 8},
                                                         {"MET_ULONG_LONG", 8}, {"MET_FLOAT", 4}, {"MET_DOUBLE", 8}};
  const auto it = sizes.find(type);
  if (it == sizes.end()) throw Error(path, "ElementType '" + type + "' is not a scalar type this reader knows");
  return it->second;
}

// The bytes the zlib (or gzip) stream at `offset` of `file` inflates to, counted without keeping them and not beyond
// limit + 1; -1 when it is not one complete stream.
long long inflated_size(const std::string& file, long long offset, long long limit) {
  std::ifstream in(file, std::ios::binary);
  in.seekg(offset);
  z_stream z{};
  if (!in || inflateInit2(&z, 15 + 32) != Z_OK) return -1;
  std::vector<unsigned char> input(1 << 16), output(1 << 18);
  long long total = 0;
  int status = Z_OK;
  while (status == Z_OK && total <= limit) {
    if (z.avail_in == 0) {
      in.read(reinterpret_cast<char*>(input.data()), static_cast<std::streamsize>(input.size()));
      z.next_in = input.data();
      z.avail_in = static_cast<unsigned>(in.gcount());
      if (z.avail_in == 0) break;  // the data ends before the stream does
    }
    z.next_out = output.data();
    z.avail_out = static_cast<unsigned>(output.size());
    status = inflate(&z, Z_NO_FLUSH);
    total += static_cast<long long>(output.size() - z.avail_out);
  }
  inflateEnd(&z);
  return status == Z_STREAM_END || total > limit ? total : -1;
}

}  // namespace

MetaImageHeader check_metaimage_header(const std::string& path) {
  namespace fs = std::filesystem;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open");
  MetaImageHeader h;
  std::string line;
  // The header is "Key = Value" lines and ends at ElementDataFile; a header longer than this is not a MetaImage one.
  constexpr int kMaxHeaderLines = 200;
  for (int n = 0; std::getline(in, line); ++n) {
    if (n >= kMaxHeaderLines) throw Error(path, "no ElementDataFile line in the first lines: not a MetaImage header");
    const size_t eq = line.find('=');
    if (eq == std::string::npos) {
      if (trim(line).empty()) continue;
      throw Error(path, "line " + std::to_string(n + 1) + " is not 'Key = Value': not a MetaImage header");
    }
    const std::string key = trim(line.substr(0, eq));
    h.fields[key] = trim(line.substr(eq + 1));
    if (key == "ElementDataFile") {
      h.header_bytes = static_cast<long long>(in.tellg());
      break;
    }
  }
  const auto field = [&](const std::string& key) {
    const auto it = h.fields.find(key);
    if (it == h.fields.end()) throw Error(path, "the MetaImage header has no " + key);
    return it->second;
  };
  if (field("NDims") != "3") throw Error(path, "NDims is '" + field("NDims") + "'; a CT volume has 3 dimensions");
  const std::vector<double> dims = numbers(path, "DimSize", field("DimSize"), 3);
  for (int a = 0; a < 3; ++a) {
    if (dims[a] < 1 || dims[a] != std::floor(dims[a]) || dims[a] > 1e5)
      throw Error(path, "DimSize '" + field("DimSize") + "' must be three whole numbers from 1 to 100000");
    h.dims[a] = static_cast<long long>(dims[a]);
  }
  for (const char* key : {"ElementSpacing", "ElementSize"})
    if (h.fields.count(key))
      for (double s : numbers(path, key, h.fields[key], 3))
        if (!(s > 0))
          throw Error(path, std::string(key) + " '" + h.fields[key] +
                                "' must be positive: a negative spacing flips an axis, which this reader would "
                                "ignore; store the volume with positive spacing (or give its axes with --anterior "
                                "and --superior)");
  for (const char* key : {"TransformMatrix", "Rotation", "Orientation"})
    if (h.fields.count(key)) {
      const std::vector<double> m = numbers(path, key, h.fields[key], 9);
      for (int i = 0; i < 9; ++i)
        if (std::abs(m[i] - (i % 4 == 0 ? 1.0 : 0.0)) > 1e-6)
          throw Error(path, std::string(key) + " '" + h.fields[key] +
                                "' is not the identity: this reader does not apply directions; resample the "
                                "volume to identity directions (for an axis permutation: remove the matrix and give "
                                "the axes with --anterior and --superior)");
    }
  const double channels = h.fields.count("ElementNumberOfChannels")
                              ? numbers(path, "ElementNumberOfChannels", h.fields["ElementNumberOfChannels"], 1)[0]
                              : 1;
  if (!(channels >= 1 && channels <= 4) || channels != std::floor(channels))
    throw Error(path, "ElementNumberOfChannels must be a whole number from 1 to 4");
  const long long bytes =
      h.dims[0] * h.dims[1] * h.dims[2] * static_cast<long long>(channels) * element_bytes(path, field("ElementType"));
  const std::string data_file = field("ElementDataFile");
  const bool compressed = h.fields.count("CompressedData") && (h.fields["CompressedData"] == "True");
  const bool list = data_file.rfind("LIST", 0) == 0 || data_file.find('%') != std::string::npos;
  if (list || h.fields.count("HeaderSize")) return h;  // sizes checked by the reader (in a child)
  long long present = 0;
  const std::string data_path = data_file == "LOCAL" ? path : (fs::path(path).parent_path() / data_file).string();
  if (data_file == "LOCAL") {
    present = static_cast<long long>(fs::file_size(path)) - h.header_bytes;
  } else {
    const fs::path data = data_path;
    std::error_code ec;
    const auto size = fs::file_size(data, ec);
    if (ec) throw Error(path, "its data file '" + data.string() + "' cannot be read: " + ec.message());
    present = static_cast<long long>(size);
  }
  if (compressed) {
    const auto declared = h.fields.find("CompressedDataSize");
    if (declared == h.fields.end())
      throw Error(path, "compressed data without a CompressedDataSize: its completeness cannot be checked");
    if (numbers(path, "CompressedDataSize", declared->second, 1)[0] != static_cast<double>(present))
      throw Error(path, "CompressedDataSize " + declared->second + " does not match the " + std::to_string(present) +
                            " bytes of compressed data present (a truncated or mismatched file)");
    // MetaIO reads a damaged stream without an error, as zeros: inflate it here (counting, keeping nothing).
    const long long inflated = inflated_size(data_path, data_file == "LOCAL" ? h.header_bytes : 0, bytes);
    if (inflated != bytes)
      throw Error(path, "DimSize " + field("DimSize") + " of " + field("ElementType") + " needs " +
                            std::to_string(bytes) + " bytes of data, the compressed data " +
                            (inflated < 0 ? std::string("is not a complete zlib stream")
                                          : "inflates to " +
                                                (inflated > bytes ? std::string("more") : std::to_string(inflated))) +
                            " (a damaged or mismatched file)");
    return h;
  }
  if (present != bytes)
    throw Error(path, "DimSize " + field("DimSize") + " of " + field("ElementType") + " needs " +
                          std::to_string(bytes) + " bytes of data, the file holds " + std::to_string(present) +
                          " (a truncated or mismatched data file)");
  return h;
}

}  // namespace facehex
