#pragma once
// The header of a NIfTI-1 volume (.nii, .nii.gz), checked before VTK's reader sees the file: VTK trusts the header's
// sizes and takes the absolute value of a negative voxel size. Here a header that does not match the data after it,
// or that describes something other than a 3-D scalar volume with positive voxel sizes, is refused with the reason.
// The orientation (qform / sform) is applied after reading (ct_volume.cpp), not here.
#include <array>
#include <string>

namespace facehex {

struct NiftiHeader {
  std::array<long long, 3> dims = {0, 0, 0};
  std::array<double, 3> spacing = {0, 0, 0};  // mm
  int bytes_per_voxel = 0;
  long long data_offset = 0;  // vox_offset
};

// Checks sizeof_hdr (348, either byte order), the single-file magic "n+1", dim (3-D; further dimensions of size 1),
// a scalar datatype and its bitpix, positive finite pixdim[1..3], finite scl_slope / scl_inter, and that the
// (decompressed) file holds exactly vox_offset plus the voxels the sizes need. NIfTI-2 and header/image pairs are
// refused. Throws Error(path, ...) naming the field at fault.
NiftiHeader check_nifti_header(const std::string& path);

}  // namespace facehex
