#include "core/segment/ct_volume.h"

#include <gtest/gtest.h>
#include <vtkMetaImageReader.h>
#include <vtkNIFTIImageWriter.h>
#include <vtkNew.h>

#include <cstdint>
#include <filesystem>
#include <fstream>

#include "core/segment/voxel_grid.h"
#include "core/util/error.h"
#include "tests/core/io/io_test_util.h"

namespace facehex {
namespace {

// A 3 x 4 x 5 MetaImage volume whose voxel value is i + 10 j + 100 k.
std::string write_small_mhd(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  std::ofstream header(dir / "small.mhd");
  header << "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
            "ElementSpacing = 0.5 1 2\nOffset = 10 20 30\nDimSize = 3 4 5\nElementType = MET_SHORT\n"
            "ElementDataFile = small.raw\n";
  std::ofstream raw(dir / "small.raw", std::ios::binary);
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 3; ++i) {
        const std::int16_t v = static_cast<std::int16_t>(i + 10 * j + 100 * k);
        raw.write(reinterpret_cast<const char*>(&v), sizeof v);
      }
  return (dir / "small.mhd").string();
}

// A folder of the running test's own (ctest may run several tests of this program at once).
std::filesystem::path scratch() {
  return test::program_scratch_dir() / ::testing::UnitTest::GetInstance()->current_test_info()->name();
}

TEST(CtVolume, ReadsMetaImageWithSpacingAndOrigin) {
  const CtVolume ct = read_ct_volume(write_small_mhd(scratch()));
  const GridGeometry& g = ct.intensity.geometry;
  EXPECT_EQ(g.dims, (std::array<int, 3>{3, 4, 5}));
  EXPECT_TRUE(g.spacing.isApprox(Eigen::Vector3d(0.5, 1, 2)));
  EXPECT_TRUE(g.origin.isApprox(Eigen::Vector3d(10, 20, 30)));
  EXPECT_EQ(ct.intensity(2, 3, 4), 432.0f);
}

// The file's own voxel type is converted to the volume's floats value for value, whatever it is.
TEST(CtVolume, ReadsEveryVoxelTypeAsItsValues) {
  const std::filesystem::path dir = scratch();
  std::filesystem::create_directories(dir);
  const auto write = [&](const std::string& type, auto sample) {
    std::ofstream header(dir / (type + ".mhd"));
    header << "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
              "ElementSpacing = 1 1 1\nDimSize = 2 3 4\nElementType = "
           << type << "\nElementDataFile = " << type << ".raw\n";
    std::ofstream raw(dir / (type + ".raw"), std::ios::binary);
    for (int n = 0; n < 24; ++n) {
      const auto v = static_cast<decltype(sample)>(n * 10 + 3);
      raw.write(reinterpret_cast<const char*>(&v), sizeof v);
    }
    return (dir / (type + ".mhd")).string();
  };
  for (const std::string& path :
       {write("MET_UCHAR", std::uint8_t{}), write("MET_USHORT", std::uint16_t{}), write("MET_INT", std::int32_t{}),
        write("MET_FLOAT", float{}), write("MET_DOUBLE", double{})}) {
    const CtVolume ct = read_ct_volume(path);
    ASSERT_EQ(ct.intensity.data.size(), 24u) << path;
    for (int n = 0; n < 24; ++n) EXPECT_EQ(ct.intensity.data[n], static_cast<float>(n * 10 + 3)) << path;
  }
}

TEST(CtVolume, ReorientsSoThatAnteriorIsPlusYAndSuperiorPlusZ) {
  // The file's -z is anterior and its +y superior: new y = old -z, new z = old y, new x = y cross z = old x.
  const CtVolume ct = read_ct_volume(write_small_mhd(scratch()), {"-z", "+y"});
  const GridGeometry& g = ct.intensity.geometry;
  EXPECT_EQ(g.dims, (std::array<int, 3>{3, 5, 4}));
  EXPECT_TRUE(g.spacing.isApprox(Eigen::Vector3d(0.5, 2, 1)));
  // New voxel (i, j, k) is old (i, k, 4 - j).
  EXPECT_EQ(ct.intensity(1, 0, 2), 1 + 10 * 2 + 100 * 4);
  EXPECT_EQ(ct.intensity(1, 4, 2), 1 + 10 * 2);
  EXPECT_NEAR(g.origin.y(), -(30 + 4 * 2), 1e-12);  // physical y = -old z
}

// The small volume written as compressed NIfTI by VTK's writer, with a rescale slope and intercept in its header (as
// scanners store Hounsfield units): read back with the same grid, spacing and rescaled values.
TEST(CtVolume, ReadsNiftiWithItsRescaleSlopeAndIntercept) {
  vtkNew<vtkMetaImageReader> mhd;
  mhd->SetFileName(write_small_mhd(scratch()).c_str());
  vtkNew<vtkNIFTIImageWriter> nifti;
  nifti->SetInputConnection(mhd->GetOutputPort());
  nifti->SetRescaleSlope(2.0);
  nifti->SetRescaleIntercept(-1000.0);
  const std::string path = (scratch() / "small.nii.gz").string();
  nifti->SetFileName(path.c_str());
  nifti->Write();
  ASSERT_TRUE(std::filesystem::exists(path));
  const CtVolume ct = read_ct_volume(path);
  const GridGeometry& g = ct.intensity.geometry;
  EXPECT_EQ(g.dims, (std::array<int, 3>{3, 4, 5}));
  EXPECT_TRUE(g.spacing.isApprox(Eigen::Vector3d(0.5, 1, 2)));
  EXPECT_EQ(ct.intensity(0, 0, 0), -1000.0f);
  EXPECT_EQ(ct.intensity(2, 3, 4), 2.0f * 432 - 1000);
}

// Resampled to a grid twice as fine over the same box (the values are linear in the voxel index, so trilinear
// interpolation is exact), written as .mha and read back: same grid, same values.
TEST(CtVolume, ResampledVolumeWrittenAsMetaImageReadsBack) {
  const CtVolume ct = read_ct_volume(write_small_mhd(scratch()));
  GridGeometry fine = ct.intensity.geometry;
  fine.dims = {5, 7, 9};
  fine.spacing /= 2;
  const CtVolume resampled{resample(ct.intensity, fine), "resampled"};
  EXPECT_FLOAT_EQ(resampled.intensity(1, 1, 1), 0.5f + 10 * 0.5f + 100 * 0.5f);
  EXPECT_FLOAT_EQ(resampled.intensity(4, 6, 8), 432.0f);
  const std::string path = (scratch() / "fine.mha").string();
  write_ct_volume(path, resampled);
  const CtVolume back = read_ct_volume(path);
  EXPECT_EQ(back.intensity.geometry.dims, fine.dims);
  EXPECT_TRUE(back.intensity.geometry.spacing.isApprox(fine.spacing));
  EXPECT_TRUE(back.intensity.geometry.origin.isApprox(fine.origin));
  EXPECT_EQ(back.intensity.data, resampled.intensity.data);
  EXPECT_THROW(write_ct_volume((scratch() / "fine.mhd").string(), resampled), Error);
  EXPECT_THROW(write_ct_volume("/no/such/folder/fine.mha", resampled), Error);
}

// MetaIO reads damaged compressed data as zeros, and prints its complaints straight to stderr: the file is refused
// naming it, and nothing comes before that one-line error.
TEST(CtVolume, AMetaImageWithDamagedCompressedDataIsRefusedQuietly) {
  const auto dir = scratch();
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "damaged.mha").string();
  std::ofstream(path, std::ios::binary) << "ObjectType = Image\nNDims = 3\nBinaryData = True\nCompressedData = True\n"
                                           "CompressedDataSize = 16\nDimSize = 4 4 4\nElementType = MET_SHORT\n"
                                           "ElementDataFile = LOCAL\n0123456789abcdef";
  ::testing::internal::CaptureStderr();
  try {
    read_ct_volume(path);
    ADD_FAILURE() << "read";
  } catch (const Error& e) {
    EXPECT_EQ(e.subject(), path) << e.what();
    EXPECT_NE(std::string(e.what()).find("the compressed data is not a complete zlib stream"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST(CtVolume, ErrorsNameTheFile) {
  try {
    read_ct_volume("/no/such/file.nii.gz");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.subject(), "/no/such/file.nii.gz");
  }
  const auto dir = scratch();
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "volume.xyz") << "not a volume";
  EXPECT_THROW(read_ct_volume((dir / "volume.xyz").string()), Error);
  std::ofstream(dir / "broken.mhd") << "ObjectType = Image\nNDims = 3\n";
  EXPECT_THROW(read_ct_volume((dir / "broken.mhd").string()), Error);
  EXPECT_THROW(read_ct_volume(write_small_mhd(dir), {"+q", "+z"}), Error);
  EXPECT_THROW(read_ct_volume(write_small_mhd(dir), {"+z", "-z"}), Error);
}

}  // namespace
}  // namespace facehex
