#pragma once
// The header of a MetaImage volume (.mhd with its data file, or .mha with the data after the header), checked before
// VTK's reader sees the file: VTK trusts the header's sizes (a bad NDims can make it loop, a DimSize larger than the
// data reads past it) and ignores spacing signs and the direction matrix. Here a volume whose header does not match
// its data, or whose axes would be silently flipped, is refused with the reason.
#include <array>
#include <map>
#include <string>

namespace facehex {

struct MetaImageHeader {
  std::map<std::string, std::string> fields;  // "NDims" -> "3", ...
  std::array<long long, 3> dims = {0, 0, 0};
  long long header_bytes = 0;  // .mha: where the data starts
};

// Reads and checks the header: NDims 3, three positive DimSize values, positive ElementSpacing, a known ElementType,
// an identity TransformMatrix (other directions are not applied by the reader: refused rather than ignored), and,
// for uncompressed data, a data file (or a LOCAL data part) holding exactly the bytes the sizes need, for compressed
// data, a stream of CompressedDataSize bytes that inflates to exactly those bytes (MetaIO reads a damaged one as
// zeros without a word).
// Throws Error(path, ...) naming the field at fault.
MetaImageHeader check_metaimage_header(const std::string& path);

}  // namespace facehex
