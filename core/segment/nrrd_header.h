#pragma once
// The header of an NRRD volume (.nrrd with its data attached, or .nhdr naming a data file), checked before VTK's
// reader sees the file: VTK trusts the sizes and reads "space directions" only for their lengths. Here a header that
// does not match its raw data, or whose directions would be ignored, is refused with the reason.
#include <array>
#include <string>

namespace facehex {

struct NrrdHeader {
  std::array<long long, 3> dims = {0, 0, 0};
  int bytes_per_voxel = 0;
  // The "space" field names RAS ("right-anterior-superior", "RAS", or the same with time): the physical
  // coordinates are RAS; else (LPS, another space or none) they are taken as LPS.
  bool ras_space = false;
};

// Checks the magic, a text header, dimension 3, three positive sizes (the first at least 10: VTK takes a shorter one
// for vector components), a scalar type, positive spacings, "space
// directions" along the axes with positive lengths (others are not applied by the reader: refused rather than
// ignored), a raw, gzip or text encoding, and that the data (after the header, or in the data file) is exactly the
// bytes the sizes need (raw) or could hold them (gzip, text).
// Throws Error(path, ...) naming the field at fault.
NrrdHeader check_nrrd_header(const std::string& path);

}  // namespace facehex
