#include "core/segment/nrrd_header.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "core/util/error.h"

namespace facehex {
namespace {

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

int type_bytes(const std::string& path, const std::string& type) {
  static const std::map<std::string, int> bytes = {{"signed char", 1},
                                                   {"int8", 1},
                                                   {"int8_t", 1},
                                                   {"uchar", 1},
                                                   {"unsigned char", 1},
                                                   {"uint8", 1},
                                                   {"uint8_t", 1},
                                                   {"short", 2},
                                                   {"short int", 2},
                                                   {"signed short", 2},
                                                   {"signed short int", 2},
                                                   {"int16", 2},
                                                   {"int16_t", 2},
                                                   {"ushort", 2},
                                                   {"unsigned short", 2},
                                                   {"unsigned short int", 2},
                                                   {"uint16", 2},
                                                   {"uint16_t", 2},
                                                   {"int", 4},
                                                   {"signed int", 4},
                                                   {"int32", 4},
                                                   {"int32_t", 4},
                                                   {"uint", 4},
                                                   {"unsigned int", 4},
                                                   {"uint32", 4},
                                                   {"uint32_t", 4},
                                                   {"float", 4},
                                                   {"double", 8},
                                                   {"longlong", 8},
                                                   {"long long", 8},
                                                   {"int64", 8},
                                                   {"ulonglong", 8},
                                                   {"unsigned long long", 8},
                                                   {"uint64", 8}};
  const auto it = bytes.find(type);
  if (it == bytes.end()) throw Error(path, "NRRD type '" + type + "' is not a scalar type this reader takes");
  return it->second;
}

std::vector<double> numbers(const std::string& path, const std::string& key, const std::string& text) {
  std::istringstream in(text);
  std::vector<double> v;
  for (std::string word; in >> word;) {
    char* end = nullptr;
    const double x = std::strtod(word.c_str(), &end);
    if (*end != '\0' || !std::isfinite(x)) throw Error(path, "NRRD " + key + " '" + text + "' is not 3 numbers");
    v.push_back(x);
  }
  if (v.size() != 3) throw Error(path, "NRRD " + key + " '" + text + "' is not 3 numbers");
  return v;
}

}  // namespace

NrrdHeader check_nrrd_header(const std::string& path) {
  namespace fs = std::filesystem;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open");
  std::string line;
  if (!std::getline(in, line) || line.rfind("NRRD000", 0) != 0) throw Error(path, "not an NRRD file (no NRRD magic)");
  // The magic is NRRD0001 to NRRD0005; VTK's reader loops on a magic line with other bytes after its version.
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line.size() != 8 || line[7] < '1' || line[7] > '5')
    throw Error(path, "the NRRD magic line is not NRRD0001 to NRRD0005");
  std::map<std::string, std::string> fields;
  // The header ends at a blank line (then the data follows) or, in a detached header, at the end of the file.
  constexpr int kMaxHeaderLines = 200;
  for (int n = 0; std::getline(in, line) && !trim(line).empty(); ++n) {
    if (n >= kMaxHeaderLines) throw Error(path, "the NRRD header does not end in its first lines");
    if (std::any_of(line.begin(), line.end(), [](unsigned char c) { return c < 0x20 && c != '\t' && c != '\r'; }))
      throw Error(path, "line " + std::to_string(n + 2) + " of the NRRD header is not text");
    if (line[0] == '#') continue;
    const size_t colon = line.find(':');
    if (colon == std::string::npos) throw Error(path, "NRRD header line '" + line + "' is not 'field: value'");
    const size_t value = line.compare(colon, 2, ":=") == 0 ? colon + 2 : colon + 1;  // key/value pairs too
    std::string key = trim(line.substr(0, colon));
    std::transform(key.begin(), key.end(), key.begin(), [](unsigned char c) { return std::tolower(c); });
    fields[key] = trim(line.substr(value));
  }
  const long long header_end =
      in.eof() ? static_cast<long long>(fs::file_size(path)) : static_cast<long long>(in.tellg());
  const auto field = [&](const std::string& key) {
    const auto it = fields.find(key);
    if (it == fields.end()) throw Error(path, "the NRRD header has no '" + key + "'");
    return it->second;
  };
  if (field("dimension") != "3") throw Error(path, "NRRD dimension is '" + field("dimension") + "'; a CT volume has 3");
  NrrdHeader h;
  if (fields.count("space")) {
    std::string space = fields["space"];
    std::transform(space.begin(), space.end(), space.begin(), [](unsigned char c) { return std::tolower(c); });
    h.ras_space = space == "right-anterior-superior" || space == "ras" || space == "right-anterior-superior-time" ||
                  space == "rast";
  }
  const std::vector<double> sizes = numbers(path, "sizes", field("sizes"));
  for (int a = 0; a < 3; ++a) {
    if (sizes[a] < 1 || sizes[a] > 1e5 || sizes[a] != std::floor(sizes[a]))
      throw Error(path, "NRRD sizes '" + field("sizes") + "' must be three whole numbers from 1 to 100000");
    h.dims[a] = static_cast<long long>(sizes[a]);
  }
  // VTK's reader takes a first axis this short for the components of a 2-D image (NRRD does not tell them apart).
  constexpr long long kMinFirstAxis = 10;
  if (h.dims[0] < kMinFirstAxis)
    throw Error(path, "NRRD sizes '" + field("sizes") + "': a first axis of fewer than " +
                          std::to_string(kMinFirstAxis) + " samples would be read as the components of a 2-D image");
  h.bytes_per_voxel = type_bytes(path, field("type"));
  if (fields.count("spacings"))
    for (double s : numbers(path, "spacings", fields["spacings"]))
      if (!(s > 0)) throw Error(path, "NRRD spacings '" + fields["spacings"] + "' must be positive");
  if (fields.count("space directions")) {
    std::string text = fields["space directions"];
    std::replace_if(
        text.begin(), text.end(), [](char c) { return c == '(' || c == ')' || c == ','; }, ' ');
    std::istringstream words(text);
    std::vector<double> d;
    for (double x; words >> x;) d.push_back(x);
    bool aligned = d.size() == 9 && words.eof();
    for (int a = 0; aligned && a < 3; ++a)
      for (int w = 0; w < 3; ++w) aligned = aligned && (w == a ? d[3 * a + w] > 0 : d[3 * a + w] == 0);
    if (!aligned)
      throw Error(path, "NRRD space directions '" + fields["space directions"] +
                            "' are not the axes with positive lengths: this reader does not apply directions; "
                            "resample the volume, or give its axes with --anterior and --superior after removing "
                            "them");
  }
  const std::string encoding = field("encoding");
  const bool raw = encoding == "raw", gzip = encoding == "gzip" || encoding == "gz",
             text = encoding == "ascii" || encoding == "text" || encoding == "txt";
  if (!raw && !gzip && !text) throw Error(path, "NRRD encoding '" + encoding + "' is not raw, gzip or text");
  const auto skips = [&](const char* key) { return fields.count(key) && fields[key] != "0"; };
  // Data split over several files (a list, or a numbered name): VTK's reader can loop on a damaged list, and a CT
  // comes as one file.
  const auto data_file = fields.find("data file") != fields.end() ? fields.find("data file") : fields.find("datafile");
  if (data_file != fields.end() &&
      (data_file->second.rfind("LIST", 0) == 0 || data_file->second.find('%') != std::string::npos))
    throw Error(path, "its data are split over several files ('data file: " + data_file->second.substr(0, 40) +
                          "'); join them into one NRRD file");
  // Data after skipped lines or bytes: left to the reader (in a child).
  if (skips("line skip") || skips("lineskip") || skips("byte skip") || skips("byteskip")) return h;
  const long long needed = h.dims[0] * h.dims[1] * h.dims[2] * h.bytes_per_voxel;
  long long present = 0;
  if (data_file == fields.end()) {
    present = static_cast<long long>(fs::file_size(path)) - header_end;
  } else {
    const fs::path data = fs::path(path).parent_path() / data_file->second;
    std::error_code ec;
    const auto size = fs::file_size(data, ec);
    if (ec) throw Error(path, "its data file '" + data.string() + "' cannot be read: " + ec.message());
    present = static_cast<long long>(size);
  }
  // Compressed data holds at most zlib's largest ratio less, text data a digit and a separator per voxel.
  const long long least = raw ? needed : gzip ? needed / 1032 : 2 * (needed / h.bytes_per_voxel) - 1;
  if (present < least || (raw && present != needed))
    throw Error(path, "NRRD sizes " + field("sizes") + " of " + field("type") + " need " +
                          (raw ? std::to_string(needed) + " bytes of raw data"
                               : "at least " + std::to_string(least) + " bytes of " + encoding + " data") +
                          ", the file holds " + std::to_string(present) + " (a truncated or mismatched file)");
  return h;
}

}  // namespace facehex
