// DICOM series folders: written slice by slice with GDCM's writer here (CT Image Storage, explicit VR little
// endian), read back by the product: sorted by position, rescaled, oriented from ImageOrientationPatient; several
// series, uneven spacing and empty folders are errors naming the folder.
#include "core/segment/dicom_series.h"

#include <gdcmAttribute.h>
#include <gdcmImageWriter.h>
#include <gdcmMediaStorage.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/segment/ct_volume.h"
#include "core/util/error.h"
#include "core/util/resources.h"

namespace facehex {
namespace {

namespace fs = std::filesystem;

struct SliceSpec {
  int nx = 3, ny = 2;
  double spacing_x = 0.5, spacing_y = 0.7;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::array<double, 6> cosines = {1, 0, 0, 0, 1, 0};  // axial, LPS: rows towards L (+x), columns towards P (+y)
  double slope = 1, intercept = 0;
  std::string series_uid = "1.2.826.0.1.3680043.9.7777.1";
  std::string description = "axial";
};

void write_slice(const std::string& path, const SliceSpec& s, const std::vector<std::int16_t>& raw) {
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
  ASSERT_TRUE(writer.Write()) << path;
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("facehex_dicom_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Four 3 x 2 slices 2.5 mm apart, written in scrambled file order; raw value i + 10 j + 100 k (k: position order),
// slope 2, intercept -1000.
fs::path write_small_series(const std::string& name, const SliceSpec& base = {}) {
  const fs::path dir = fresh_dir(name);
  const char* files[4] = {"c.dcm", "a.dcm", "d.dcm", "b.dcm"};
  for (int k = 0; k < 4; ++k) {
    SliceSpec s = base;
    s.slope = 2;
    s.intercept = -1000;
    s.position = base.position + k * 2.5 * Eigen::Vector3d(0, 0, 1);
    std::vector<std::int16_t> raw;
    for (int j = 0; j < s.ny; ++j)
      for (int i = 0; i < s.nx; ++i) raw.push_back(static_cast<std::int16_t>(i + 10 * j + 100 * k));
    write_slice((dir / files[k]).string(), s, raw);
  }
  return dir;
}

TEST(DicomSeries, SlicesAreSortedByPositionRescaledAndOriented) {
  const fs::path dir = write_small_series("sorted");
  std::ofstream(dir / "README.txt") << "not DICOM";  // skipped
  const DicomVolume v = read_dicom_series(dir.string());
  const GridGeometry& g = v.intensity.geometry;
  EXPECT_EQ(g.dims, (std::array<int, 3>{3, 2, 4}));
  EXPECT_TRUE(g.spacing.isApprox(Eigen::Vector3d(0.5, 0.7, 2.5))) << g.spacing.transpose();
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) EXPECT_EQ(v.intensity(i, j, k), 2.0f * (i + 10 * j + 100 * k) - 1000) << i << j << k;
  EXPECT_EQ(v.anterior, "-y");  // LPS: columns run posterior
  EXPECT_EQ(v.superior, "+z");

  // read_ct_volume takes that orientation unless told another.
  const CtVolume automatic = read_ct_volume(dir.string());
  const CtVolume stated = read_ct_volume(dir.string(), {"-y", "+z"});
  const CtVolume wrong = read_ct_volume(dir.string(), {"+y", "+z"});
  EXPECT_EQ(automatic.intensity.data, stated.intensity.data);
  EXPECT_NE(automatic.intensity.data, wrong.intensity.data);
}

TEST(DicomSeries, SeveralSeriesInOneFolderAreAnErrorListingThem) {
  const fs::path dir = write_small_series("mixed");
  SliceSpec localizer;
  localizer.series_uid = "1.2.826.0.1.3680043.9.7777.2";
  localizer.description = "localizer";
  write_slice((dir / "scout.dcm").string(), localizer, std::vector<std::int16_t>(6, 5));
  const std::vector<DicomSeries> series = dicom_series_in(dir.string());
  ASSERT_EQ(series.size(), 2u);
  EXPECT_EQ(series[0].files.size(), 4u);  // largest first
  EXPECT_EQ(series[1].description, "localizer");
  try {
    read_ct_volume(dir.string());
    FAIL() << "mixed series accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.subject(), dir.string());
    const std::string message = e.what();
    EXPECT_NE(message.find("2 DICOM series"), std::string::npos) << message;
    EXPECT_NE(message.find("1.2.826.0.1.3680043.9.7777.2 (localizer)"), std::string::npos) << message;
    EXPECT_NE(message.find("folder of its own"), std::string::npos) << message;
  }
}

TEST(DicomSeries, UnevenSpacingDuplicatePositionsAndEmptyFoldersAreErrors) {
  const fs::path uneven = write_small_series("uneven");
  SliceSpec far;
  far.position = Eigen::Vector3d(0, 0, 20);
  write_slice((uneven / "e.dcm").string(), far, std::vector<std::int16_t>(6, 1));
  EXPECT_THROW(read_dicom_series(uneven.string()), Error);

  const fs::path duplicate = write_small_series("duplicate");
  SliceSpec again;
  again.position = Eigen::Vector3d(0, 0, 2.5);
  write_slice((duplicate / "e.dcm").string(), again, std::vector<std::int16_t>(6, 1));
  EXPECT_THROW(read_dicom_series(duplicate.string()), Error);

  const fs::path empty = fresh_dir("empty");
  std::ofstream(empty / "notes.txt") << "nothing here";
  try {
    read_ct_volume(empty.string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no DICOM image"), std::string::npos) << e.what();
  }
}

// The bundled CT written as a DICOM series the way scanners store axial slices (LPS: rows towards the patient's left,
// columns towards posterior; the segmentation frame's +x is the patient's right, +y anterior), one file per slice in
// reverse name order, reads back as the same volume in the segmentation frame: the orientation comes from the files,
// not from an option.
TEST(DicomSeries, BundledCtAsADicomSeriesReadsBackAsTheSameVolume) {
  const CtVolume ct = read_ct_volume(default_ct());
  const GridGeometry& g = ct.intensity.geometry;
  const fs::path dir = fresh_dir("bundled");
  for (int k = 0; k < g.dims[2]; ++k) {
    SliceSpec s;
    s.nx = g.dims[0];
    s.ny = g.dims[1];
    s.spacing_x = g.spacing(0);
    s.spacing_y = g.spacing(1);
    s.cosines = {1, 0, 0, 0, 1, 0};
    s.position = Eigen::Vector3d(0, 0, g.origin(2) + k * g.spacing(2));  // superior: +z LPS
    std::vector<std::int16_t> raw;  // row j of the file is our y = ny - 1 - j; column i our x = nx - 1 - i
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i)
        raw.push_back(static_cast<std::int16_t>(ct.intensity(g.dims[0] - 1 - i, g.dims[1] - 1 - j, k)));
    write_slice((dir / ("slice" + std::to_string(g.dims[2] - k) + ".dcm")).string(), s, raw);
  }
  const CtVolume back = read_ct_volume(dir.string());
  EXPECT_EQ(back.intensity.geometry.dims, g.dims);
  EXPECT_TRUE(back.intensity.geometry.spacing.isApprox(g.spacing, 1e-6));
  EXPECT_EQ(back.intensity.data, ct.intensity.data);
}

}  // namespace
}  // namespace facehex
