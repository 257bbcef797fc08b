#pragma once
// DICOM slices written with GDCM's writer (CT Image Storage, explicit VR little endian), for the tests that read
// DICOM folders: the reader's own tests and the desktop application's.
#include <gdcmAttribute.h>
#include <gdcmImageWriter.h>
#include <gdcmMediaStorage.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/segment/ct_volume.h"
#include "core/util/resources.h"

namespace facehex::testing {

struct SliceSpec {
  int nx = 3, ny = 2;
  double spacing_x = 0.5, spacing_y = 0.7;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::array<double, 6> cosines = {1, 0, 0, 0, 1, 0};  // axial, LPS: rows towards L (+x), columns towards P (+y)
  double slope = 1, intercept = 0;
  std::string series_uid = "1.2.826.0.1.3680043.9.7777.1";
  std::string description = "axial";
};

inline void write_slice(const std::string& path, const SliceSpec& s, const std::vector<std::int16_t>& raw) {
  gdcm::ImageWriter writer;
  gdcm::Image& image = writer.GetImage();
  image.SetNumberOfDimensions(2);
  image.SetDimension(0, static_cast<unsigned int>(s.nx));
  image.SetDimension(1, static_cast<unsigned int>(s.ny));
  image.SetPhotometricInterpretation(gdcm::PhotometricInterpretation::MONOCHROME2);
  image.SetPixelFormat(gdcm::PixelFormat::INT16);
  image.SetSpacing(0, s.spacing_x);
  image.SetSpacing(1, s.spacing_y);
  for (unsigned int a = 0; a < 3; ++a) image.SetOrigin(a, s.position(a));
  image.SetDirectionCosines(s.cosines.data());
  image.SetSlope(s.slope);
  image.SetIntercept(s.intercept);
  gdcm::DataElement pixels(gdcm::Tag(0x7fe0, 0x0010));
  pixels.SetByteValue(reinterpret_cast<const char*>(raw.data()), static_cast<uint32_t>(raw.size() * sizeof raw[0]));
  image.SetDataElement(pixels);
  gdcm::DataSet& ds = writer.GetFile().GetDataSet();
  const char* ct_storage = gdcm::MediaStorage::GetMSString(gdcm::MediaStorage::CTImageStorage);
  gdcm::DataElement sop_class(gdcm::Tag(0x0008, 0x0016));
  sop_class.SetByteValue(ct_storage, static_cast<uint32_t>(std::strlen(ct_storage)));
  sop_class.SetVR(gdcm::Attribute<0x0008, 0x0016>::GetVR());
  ds.Insert(sop_class);
  gdcm::Attribute<0x0020, 0x000e> series;
  series.SetValue(s.series_uid);
  ds.Replace(series.GetAsDataElement());
  gdcm::Attribute<0x0008, 0x103e> description;
  description.SetValue(s.description);
  ds.Replace(description.GetAsDataElement());
  writer.SetFileName(path.c_str());
  if (!writer.Write()) throw std::runtime_error("GDCM could not write " + path);
}

// The bundled CT written as an LPS series, slice k's window and content moved forward (LPS -y) by rows_forward(k)
// rows: its origin moves with it, as a gantry tilt shears a stack; what a window gains in front of the CT is air.
inline void write_bundled_series(const std::filesystem::path& dir, const std::function<int(int)>& rows_forward) {
  const CtVolume ct = read_ct_volume(default_ct());
  const GridGeometry& g = ct.intensity.geometry;
  for (int k = 0; k < g.dims[2]; ++k) {
    SliceSpec s;
    s.nx = g.dims[0];
    s.ny = g.dims[1];
    s.spacing_x = g.spacing(0);
    s.spacing_y = g.spacing(1);
    s.position = Eigen::Vector3d(0, -rows_forward(k) * g.spacing(1), g.origin(2) + k * g.spacing(2));
    std::vector<std::int16_t> raw;  // the file's row j is our y = ny - 1 - j + shift; column i our x = nx - 1 - i
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const int y = g.dims[1] - 1 - j + rows_forward(k);
        raw.push_back(static_cast<std::int16_t>(y < g.dims[1] ? ct.intensity(g.dims[0] - 1 - i, y, k) : 0));
      }
    write_slice((dir / ("slice" + std::to_string(g.dims[2] - k) + ".dcm")).string(), s, raw);  // reverse name order
  }
}

}  // namespace facehex::testing
