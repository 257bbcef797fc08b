#include "core/segment/nifti_header.h"

#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "core/util/error.h"

namespace facehex {
namespace {

constexpr int kHeaderBytes = 348;
// Larger than any CT this tool segments (and than the reading child's memory budget): refused before any reading.
constexpr long long kMaxDataBytes = 8LL << 30;

// The header's bytes, in the file's byte order (swapped to ours when sizeof_hdr says so).
class RawHeader {
 public:
  RawHeader(const unsigned char* bytes, bool swap) : swap_(swap) { std::memcpy(bytes_, bytes, kHeaderBytes); }
  template <class T>
  T at(int offset) const {
    unsigned char b[sizeof(T)];
    std::memcpy(b, bytes_ + offset, sizeof(T));
    if (swap_)
      for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    T value;
    std::memcpy(&value, b, sizeof(T));
    return value;
  }
  std::string text(int offset, int size) const {
    return std::string(reinterpret_cast<const char*>(bytes_ + offset), size);
  }

 private:
  unsigned char bytes_[kHeaderBytes];
  bool swap_;
};

int voxel_bytes(const std::string& path, int datatype, int bitpix) {
  // NIfTI-1 scalar datatypes: uint8, int16, int32, float32, float64, int8, uint16, uint32, int64, uint64.
  static const std::map<int, int> bytes = {{2, 1},   {4, 2},   {8, 4},   {16, 4},   {64, 8},
                                           {256, 1}, {512, 2}, {768, 4}, {1024, 8}, {1280, 8}};
  const auto it = bytes.find(datatype);
  if (it == bytes.end())
    throw Error(path, "NIfTI datatype " + std::to_string(datatype) + " is not a scalar type this reader takes");
  if (bitpix != 8 * it->second)
    throw Error(path, "NIfTI bitpix " + std::to_string(bitpix) + " does not match datatype " +
                          std::to_string(datatype) + " (" + std::to_string(8 * it->second) + " bits)");
  return it->second;
}

}  // namespace

NiftiHeader check_nifti_header(const std::string& path) {
  // zlib reads a plain file as it is and a gzip-compressed one decompressed.
  const std::unique_ptr<gzFile_s, int (*)(gzFile)> in(gzopen(path.c_str(), "rb"), gzclose);
  if (!in) throw Error(path, "cannot open");
  unsigned char bytes[kHeaderBytes];
  if (gzread(in.get(), bytes, kHeaderBytes) != kHeaderBytes)
    throw Error(path, "shorter than a NIfTI-1 header (348 bytes)");
  std::int32_t size;
  std::memcpy(&size, bytes, 4);
  const bool swap = size != kHeaderBytes;
  const RawHeader h(bytes, swap);
  if (h.at<std::int32_t>(0) != kHeaderBytes) {
    if (size == 540 || h.at<std::int32_t>(0) == 540) throw Error(path, "NIfTI-2 files are not supported");
    throw Error(path, "not a NIfTI-1 file (sizeof_hdr is not 348)");
  }
  const std::string magic = h.text(344, 4);
  if (magic == std::string("ni1\0", 4))
    throw Error(path, "a NIfTI header without its image (a .hdr/.img pair) is not supported; convert it to .nii");
  if (magic != std::string("n+1\0", 4)) throw Error(path, "the NIfTI magic is not 'n+1'");

  NiftiHeader out;
  const int ndim = h.at<std::int16_t>(40);
  if (ndim < 3 || ndim > 7) throw Error(path, "NIfTI dim[0] is " + std::to_string(ndim) + ", a CT volume has 3");
  for (int a = 1; a <= ndim; ++a) {
    const int n = h.at<std::int16_t>(40 + 2 * a);
    if (a <= 3 && n < 1) throw Error(path, "NIfTI dim[" + std::to_string(a) + "] is " + std::to_string(n));
    if (a > 3 && n != 1)
      throw Error(path, "NIfTI dim[" + std::to_string(a) + "] is " + std::to_string(n) +
                            ": a volume with more than 3 dimensions is not a CT volume");
    if (a <= 3) out.dims[a - 1] = n;
  }
  out.bytes_per_voxel = voxel_bytes(path, h.at<std::int16_t>(70), h.at<std::int16_t>(72));
  for (int a = 0; a < 3; ++a) {
    out.spacing[a] = h.at<float>(80 + 4 * a);
    if (!(std::isfinite(out.spacing[a]) && out.spacing[a] > 0))
      throw Error(path, "NIfTI pixdim[" + std::to_string(a + 1) + "] is " + std::to_string(out.spacing[a]) +
                            ": voxel sizes must be positive (a negative one flips an axis, which VTK would ignore)");
  }
  for (const auto& [offset, name] : {std::pair{112, "scl_slope"}, std::pair{116, "scl_inter"}})
    if (!std::isfinite(h.at<float>(offset))) throw Error(path, std::string("NIfTI ") + name + " is not finite");
  const float vox_offset = h.at<float>(108);
  if (!(vox_offset >= 352 && vox_offset < 1e9) || vox_offset != std::floor(vox_offset))
    throw Error(path, "NIfTI vox_offset " + std::to_string(vox_offset) + " is not a whole number from 352");
  out.data_offset = static_cast<long long>(vox_offset);
  const long long data = out.dims[0] * out.dims[1] * out.dims[2] * out.bytes_per_voxel;
  if (data > kMaxDataBytes)
    throw Error(path, "NIfTI dims " + std::to_string(out.dims[0]) + " x " + std::to_string(out.dims[1]) + " x " +
                          std::to_string(out.dims[2]) + " need more than 8 GB: larger than this reader takes");

  // The bytes after the header, counted up to one more than needed (a compressed file is not decompressed further).
  const long long needed = out.data_offset + data;
  long long present = kHeaderBytes;
  std::vector<char> buffer(1 << 20);
  while (present <= needed) {
    const int n = gzread(in.get(), buffer.data(), static_cast<unsigned>(buffer.size()));
    if (n < 0) throw Error(path, "cannot read the compressed data (a damaged .gz file)");
    if (n == 0) break;
    present += n;
  }
  if (present != needed)
    throw Error(path, "NIfTI dims " + std::to_string(out.dims[0]) + " x " + std::to_string(out.dims[1]) + " x " +
                          std::to_string(out.dims[2]) + " at vox_offset " + std::to_string(out.data_offset) + " need " +
                          std::to_string(needed) + " bytes, the file holds " +
                          (present > needed ? "more" : std::to_string(present)) + " (a truncated or mismatched file)");
  return out;
}

}  // namespace facehex
