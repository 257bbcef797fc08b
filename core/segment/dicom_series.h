#pragma once
// A DICOM series folder read with GDCM.
//
// Every file of the folder (not its subfolders) is scanned; files that are not DICOM images are skipped. Scanners
// export localizers and reconstructions side by side, and stacking them would make a wrong volume: the series
// (SeriesInstanceUID) to read is named, by its UID or its number in dicom_series_in's list, or the folder must hold
// only one; several without a name are an error that lists them, numbered. The series' slices are
// sorted along their normal by ImagePositionPatient, decoded (any transfer syntax GDCM reads: raw, JPEG, JPEG-LS,
// JPEG 2000, RLE), rescaled with each slice's RescaleSlope/Intercept (Hounsfield units for CT) and stacked. A
// multi-frame file is one series by itself.
//
// Voxel axes: i along the rows (ImageOrientationPatient's first vector), j along the columns (its second), k along the
// slice normal (their cross product), in the order of increasing position. Spacing: PixelSpacing in plane, the step
// between consecutive slice positions along the normal (which must be uniform within 1 %). The origin is the first
// slice's position expressed in those axes. Slices whose positions also move in plane (a gantry tilted in the
// acquisition) are resampled onto an upright grid that holds them all (slice_shear.h), the volume's lowest value
// where a slice does not reach. anterior/superior: which voxel axis points that way in the patient (LPS:
// anterior is -y, superior +z), as "+x" ... "-z", the nearest axis for an oblique series.
#include <string>
#include <vector>

#include "core/segment/voxel_grid.h"

namespace facehex {

struct DicomSeries {
  std::string uid;
  std::string description;  // SeriesDescription, may be empty
  std::vector<std::string> files;
};

// The image series of a folder, largest first. Throws facehex::Error(folder, ...) if it is not a folder.
std::vector<DicomSeries> dicom_series_in(const std::string& folder);

struct DicomVolume {
  Field intensity;
  std::string anterior, superior;  // voxel axes, see above
  // The voxel axes in the patient's LPS frame (columns: rows, columns, normal): the intensity's physical coordinates
  // p are the patient's at patient_axes * p.
  Eigen::Matrix3d patient_axes = Eigen::Matrix3d::Identity();
  // The angle between the slices' normal and the line through their origins (a gantry tilt), in degrees; 0 when
  // their origins lie on the normal.
  double gantry_tilt_degrees = 0;
};

// `series`: the UID of the series to read, or its number in dicom_series_in(folder) (from 1, largest first); empty:
// the folder's only series. Throws facehex::Error(folder, ...) when the folder has no DICOM image, several series and
// none named, a named series it does not hold, slices of different sizes or orientations, two slices at one position,
// uneven slice spacing, or a pixel format that is not a scalar number.
DicomVolume read_dicom_series(const std::string& folder, const std::string& series = "");

// "N files of series UID (description)", the way the errors list a series.
std::string series_text(const DicomSeries& series);

// The series `name` names among `series` (dicom_series_in's list): its UID, or its number in the list from 1; null
// when none is.
const DicomSeries* named_series(const std::vector<DicomSeries>& series, const std::string& name);

}  // namespace facehex
