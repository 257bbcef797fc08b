#include "core/segment/dicom_series.h"

#include <gdcmDirectory.h>
#include <gdcmImage.h>
#include <gdcmImageReader.h>
#include <gdcmScanner.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>

#include "core/segment/slice_shear.h"
#include "core/util/error.h"

namespace facehex {
namespace {

const gdcm::Tag kSeriesUid(0x0020, 0x000e), kSeriesDescription(0x0008, 0x103e), kRows(0x0028, 0x0010);
// pixels: slice origins this close in plane lie on one line along the normal (positions are written rounded, to
// 0.01 mm or finer); a stack whose origins move further leans and is resampled upright
constexpr double kSameOrigin = 0.1;

std::string trimmed(const char* text) {
  std::string s = text ? text : "";
  while (!s.empty() && (s.back() == ' ' || s.back() == '\0')) s.pop_back();
  return s;
}

// The pixels of a decoded image as floats, slope and intercept applied.
void append_pixels(const gdcm::Image& image, const std::string& file, std::vector<float>& out) {
  std::vector<char> buffer(image.GetBufferLength());
  if (!image.GetBuffer(buffer.data())) throw Error(file, "GDCM could not decode the pixel data");
  const gdcm::PixelFormat& format = image.GetPixelFormat();
  if (format.GetSamplesPerPixel() != 1) throw Error(file, "is not a greyscale image (colour DICOM)");
  const double slope = image.GetSlope(), intercept = image.GetIntercept();
  auto convert = [&](auto tag) {
    using T = decltype(tag);
    const size_t n = buffer.size() / sizeof(T);
    for (size_t i = 0; i < n; ++i) {
      T v;
      std::memcpy(&v, buffer.data() + i * sizeof(T), sizeof(T));
      out.push_back(static_cast<float>(slope * static_cast<double>(v) + intercept));
    }
  };
  switch (format.GetScalarType()) {
    case gdcm::PixelFormat::UINT8:
      convert(std::uint8_t{});
      break;
    case gdcm::PixelFormat::INT8:
      convert(std::int8_t{});
      break;
    case gdcm::PixelFormat::UINT16:
      convert(std::uint16_t{});
      break;
    case gdcm::PixelFormat::INT16:
      convert(std::int16_t{});
      break;
    case gdcm::PixelFormat::UINT32:
      convert(std::uint32_t{});
      break;
    case gdcm::PixelFormat::INT32:
      convert(std::int32_t{});
      break;
    case gdcm::PixelFormat::FLOAT32:
      convert(float{});
      break;
    case gdcm::PixelFormat::FLOAT64:
      convert(double{});
      break;
    default:
      throw Error(file, std::string("unsupported pixel format ") + format.GetScalarTypeAsString());
  }
}

// "+x" ... "-z": the voxel axis (columns of `axes`) nearest to `direction`.
std::string nearest_axis(const Eigen::Matrix3d& axes, const Eigen::Vector3d& direction) {
  const Eigen::Vector3d d = axes.transpose() * direction;
  Eigen::Index a = 0;
  d.cwiseAbs().maxCoeff(&a);
  return std::string(d(a) > 0 ? "+" : "-") + static_cast<char>('x' + a);
}

struct Slice {
  std::string file;
  double position = 0;  // along the normal
  std::unique_ptr<gdcm::ImageReader> reader;
};

}  // namespace

std::vector<DicomSeries> dicom_series_in(const std::string& folder) {
  if (!std::filesystem::is_directory(folder)) throw Error(folder, "is not a folder");
  gdcm::Directory directory;
  directory.Load(folder, false);
  gdcm::Scanner scanner;
  scanner.AddTag(kSeriesUid);
  scanner.AddTag(kSeriesDescription);
  scanner.AddTag(kRows);
  std::vector<DicomSeries> series;
  if (directory.GetFilenames().empty() || !scanner.Scan(directory.GetFilenames())) return series;
  std::map<std::string, DicomSeries> by_uid;
  for (const std::string& file : directory.GetFilenames()) {
    if (!scanner.IsKey(file.c_str())) continue;  // not DICOM
    const gdcm::Scanner::TagToValue& values = scanner.GetMapping(file.c_str());
    if (!values.count(kRows)) continue;  // no image (a DICOMDIR, a report)
    const std::string uid = values.count(kSeriesUid) ? trimmed(values.at(kSeriesUid)) : "";
    DicomSeries& s = by_uid[uid];
    s.uid = uid;
    if (values.count(kSeriesDescription)) s.description = trimmed(values.at(kSeriesDescription));
    s.files.push_back(file);
  }
  for (auto& [uid, s] : by_uid) series.push_back(std::move(s));
  std::stable_sort(series.begin(), series.end(),
                   [](const DicomSeries& a, const DicomSeries& b) { return a.files.size() > b.files.size(); });
  return series;
}

std::string series_text(const DicomSeries& series) {
  return std::to_string(series.files.size()) + " files of series " + series.uid +
         (series.description.empty() ? "" : " (" + series.description + ")");
}

const DicomSeries* named_series(const std::vector<DicomSeries>& series, const std::string& name) {
  for (size_t i = 0; i < series.size(); ++i)
    if (series[i].uid == name || std::to_string(i + 1) == name) return &series[i];
  return nullptr;
}

DicomVolume read_dicom_series(const std::string& folder, const std::string& named) {
  const std::vector<DicomSeries> series = dicom_series_in(folder);
  if (series.empty()) throw Error(folder, "holds no DICOM image");
  const auto list = [&] {
    std::ostringstream text;
    for (size_t i = 0; i < series.size(); ++i) text << (i ? "; " : "") << i + 1 << ": " << series_text(series[i]);
    return text.str();
  };
  const DicomSeries* chosen =
      named.empty() ? (series.size() == 1 ? &series.front() : nullptr) : named_series(series, named);
  if (!chosen && named.empty())
    throw Error(folder, "holds " + std::to_string(series.size()) + " DICOM series (" + list() +
                            "): name the one to segment with --series (its number or UID)");
  if (!chosen)
    throw Error(folder, "holds no DICOM series '" + named + "' (it holds " + list() +
                            "): --series takes one of their numbers or UIDs");
  std::vector<Slice> slices(chosen->files.size());
  for (size_t i = 0; i < slices.size(); ++i) {
    Slice& s = slices[i];
    s.file = chosen->files[i];
    s.reader = std::make_unique<gdcm::ImageReader>();
    s.reader->SetFileName(s.file.c_str());
    if (!s.reader->Read()) throw Error(s.file, "GDCM could not read this DICOM image");
  }
  const gdcm::Image& first = slices.front().reader->GetImage();  // the first file's: orientation, size, spacing
  const double* cosines = first.GetDirectionCosines();
  Eigen::Matrix3d axes;  // columns: row direction, column direction, normal (patient LPS frame)
  axes.col(0) = Eigen::Vector3d(cosines[0], cosines[1], cosines[2]).normalized();
  axes.col(1) = Eigen::Vector3d(cosines[3], cosines[4], cosines[5]).normalized();
  axes.col(2) = axes.col(0).cross(axes.col(1));
  if (!axes.allFinite() || std::abs(axes.col(2).norm() - 1) > 1e-3)
    throw Error(slices.front().file, "has no valid ImageOrientationPatient");
  const unsigned int* dims = first.GetDimensions();
  for (Slice& s : slices) {
    const gdcm::Image& image = s.reader->GetImage();
    const double* c = image.GetDirectionCosines();
    for (int k = 0; k < 6; ++k)
      if (std::abs(c[k] - cosines[k]) > 1e-4)
        throw Error(s.file, "has another slice orientation than " + slices[0].file);
    if (image.GetDimension(0) != dims[0] || image.GetDimension(1) != dims[1])
      throw Error(s.file, "has another image size than " + slices[0].file);
    const double* origin = image.GetOrigin();
    s.position = axes.col(2).dot(Eigen::Vector3d(origin[0], origin[1], origin[2]));
  }
  std::sort(slices.begin(), slices.end(), [](const Slice& a, const Slice& b) { return a.position < b.position; });

  DicomVolume volume;
  GridGeometry& g = volume.intensity.geometry;
  const double* pixel_spacing = first.GetSpacing();
  g.spacing = Eigen::Vector3d(pixel_spacing[0], pixel_spacing[1], pixel_spacing[2]);
  if (slices.size() == 1) {  // one file: a multi-frame image, or a single slice (rejected later as not 3D)
    g.dims = {static_cast<int>(dims[0]), static_cast<int>(dims[1]),
              static_cast<int>(first.GetNumberOfDimensions() > 2 ? dims[2] : 1)};
  } else {
    if (first.GetNumberOfDimensions() > 2 && dims[2] > 1)
      throw Error(folder, "mixes multi-frame files with other slices of the same series");
    const double step = (slices.back().position - slices.front().position) / static_cast<double>(slices.size() - 1);
    for (size_t i = 1; i < slices.size(); ++i) {
      const double gap = slices[i].position - slices[i - 1].position;
      if (gap < 1e-6)
        throw Error(folder, slices[i].file + " and " + slices[i - 1].file + " are at the same slice position");
      if (std::abs(gap - step) > 0.01 * step)
        throw Error(folder, "the slices are not evenly spaced (" + std::to_string(gap) + " mm after " +
                                slices[i - 1].file + ", " + std::to_string(step) + " mm on average)");
    }
    g.dims = {static_cast<int>(dims[0]), static_cast<int>(dims[1]), static_cast<int>(slices.size())};
    g.spacing(2) = step;
  }
  // The lowest slice's position (the files' own order is any).
  const double* origin = slices.front().reader->GetImage().GetOrigin();
  g.origin = axes.transpose() * Eigen::Vector3d(origin[0], origin[1], origin[2]);
  volume.intensity.data.reserve(g.size());
  for (const Slice& s : slices) append_pixels(s.reader->GetImage(), s.file, volume.intensity.data);
  if (volume.intensity.data.size() != g.size()) throw Error(folder, "the decoded pixel data has the wrong size");
  // Each slice's origin in plane, from the first's: a gantry tilt moves it along the columns from slice to slice.
  std::vector<Eigen::Vector2d> offsets;
  bool sheared = false;
  for (const Slice& s : slices) {
    const double* o = s.reader->GetImage().GetOrigin();
    const Eigen::Vector3d d =
        axes.transpose() * (Eigen::Vector3d(o[0], o[1], o[2]) - Eigen::Vector3d(origin[0], origin[1], origin[2]));
    offsets.push_back(d.head<2>());
    sheared |= d.head<2>().norm() > kSameOrigin * std::min(g.spacing(0), g.spacing(1));
  }
  if (sheared) {
    const float lowest = *std::min_element(volume.intensity.data.begin(), volume.intensity.data.end());
    volume.intensity = unshear_slices(volume.intensity, offsets, lowest);
    const double along = slices.back().position - slices.front().position;
    volume.gantry_tilt_degrees = std::atan2(offsets.back().norm(), along) * 180 / M_PI;
  }
  volume.patient_axes = axes;
  volume.anterior = nearest_axis(axes, Eigen::Vector3d(0, -1, 0));  // LPS: anterior is -y
  volume.superior = nearest_axis(axes, Eigen::Vector3d(0, 0, 1));
  if (volume.anterior[1] == volume.superior[1])
    throw Error(folder, "the series is too oblique to tell its anterior from its superior axis: state them");
  return volume;
}

}  // namespace facehex
