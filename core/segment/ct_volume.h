#pragma once
// A CT volume in millimetres, in the segmentation frame: +y ANTERIOR (the face looks towards +y), +z SUPERIOR,
// +x = y x z (right-handed; which ear that is depends on the scan, see core/sides.h).
#include <string>
#include <vector>

#include "core/mesh/scan_frame.h"
#include "core/segment/voxel_grid.h"

namespace facehex {

struct CtVolume {
  Field intensity;     // file units (Hounsfield units when the file says so; any monotone scale works)
  std::string source;  // file or folder it was read from, for messages
  // A DICOM series acquired with its gantry tilted, resampled onto an upright grid (dicom_series.h): the tilt, degrees;
  // 0 otherwise.
  double gantry_tilt_degrees = 0;
  // Where the grid's physical coordinates (mm) lie in the scan's LPS patient frame (core/mesh/scan_frame.h).
  ScanFrame scan_frame = {};
};

// Which axis of the file's voxel grid points anterior and which superior: "+x", "-x", "+y", "-y", "+z" or "-z".
// Empty: the file's own orientation where it has one (a DICOM series: from ImageOrientationPatient, see
// dicom_series.h; a NIfTI file: from its sform, else its qform, refused when oblique), else the segmentation frame
// itself (+y anterior, +z superior; a MetaImage direction matrix must be the identity, NRRD space directions the
// positive axes). E.g. a volume stored in LPS order is anterior "-y", superior "+z".
struct CtOrientation {
  std::string anterior;
  std::string superior;
};

// Reads a CT volume: .mhd/.mha (MetaImage), .nii/.nii.gz (NIfTI, scl_slope/inter applied), .nrrd/.nhdr, .vti, or a
// folder holding one DICOM series (GDCM; rescale slope/intercept applied). Spacing and origin are the file's, and
// scan_frame says where the reoriented grid lies in the file's patient frame. Throws
// facehex::Error(path, ...) on a missing, unreadable, non-3D or blank (constant) volume, a DICOM folder with several
// series and none named by `dicom_series` (read_dicom_series' `series`; given for a file, an error too), or an
// invalid orientation.
CtVolume read_ct_volume(const std::string& path, const CtOrientation& orientation = {},
                        const std::string& dicom_series = "");

// Writes the volume (already in the segmentation frame) as a single-file MetaImage (.mha, float voxels) with VTK's
// writer, atomically. Throws facehex::Error(path, ...) on another extension or a failed write.
void write_ct_volume(const std::string& path, const CtVolume& ct);

// Whether `path` is a CT volume to segment (rather than a mesh): a file with one of ct_volume_extensions(), or a
// folder (of DICOM slices).
bool is_ct_input(const std::string& path);
const std::vector<std::string>& ct_volume_extensions();  // ".mhd", ".mha", ".nii", ".nii.gz", ".nrrd", ".nhdr"

// Permutes/flips the voxel grid so that `orientation.anterior` becomes +y and `orientation.superior` becomes +z; the
// scan frame follows.
CtVolume reorient(CtVolume ct, const CtOrientation& orientation);

}  // namespace facehex
