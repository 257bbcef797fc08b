#include "core/segment/ct_volume.h"

#include <gtest/gtest.h>
#include <vtkMatrix4x4.h>
#include <vtkMetaImageReader.h>
#include <vtkNIFTIImageWriter.h>
#include <vtkNew.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>

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

// Every voxel of `ct` (read from a file whose voxel (i, j, k) holds i + 10 j + 100 k) lies where the file puts voxel
// (i, j, k) in its patient frame, LPS: `scan_point(i, j, k)`.
void expect_voxels_at_their_scan_points(const CtVolume& ct,
                                        const std::function<Eigen::Vector3d(int, int, int)>& scan_point) {
  const GridGeometry& g = ct.intensity.geometry;
  for (size_t n = 0; n < g.size(); ++n) {
    const auto [i, j, k] = g.ijk(n);
    const int v = static_cast<int>(std::lround(ct.intensity.data[n]));
    const Eigen::Vector3d expected = scan_point(v % 10, (v / 10) % 10, v / 100);
    ASSERT_TRUE(ct.scan_frame.to_scan(g.point(i, j, k)).isApprox(expected, 1e-9))
        << "value " << v << ": " << ct.scan_frame.to_scan(g.point(i, j, k)).transpose() << " instead of "
        << expected.transpose();
  }
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
  // The MetaImage's physical frame is its scan frame: each voxel still lies where the file put it.
  expect_voxels_at_their_scan_points(
      ct, [](int i, int j, int k) { return Eigen::Vector3d(10 + 0.5 * i, 20 + j, 30 + 2 * k); });
  EXPECT_FALSE(ct.scan_frame.left_at_minus_x());
  EXPECT_TRUE(read_ct_volume(write_small_mhd(scratch())).scan_frame.rotation.isIdentity());
}

// NIfTI's world is RAS: the scan frame negates its x and y. Stored as scanners store LPS (rows towards the patient's
// left, columns towards posterior), or in RAS order: either way a right-handed volume read into the segmentation
// frame has the patient's left at -x.
TEST(CtVolume, ANiftiFilesVoxelsLieAtTheirWorldPointsAndItsPatientsLeftIsMinusX) {
  vtkNew<vtkMetaImageReader> mhd;
  mhd->SetFileName(write_small_mhd(scratch()).c_str());
  for (const double flip : {-1.0, 1.0}) {
    vtkNew<vtkMatrix4x4> qform;  // voxel axes i, j along RAS -x, -y (LPS order) or +x, +y; k superior
    qform->SetElement(0, 0, flip);
    qform->SetElement(1, 1, flip);
    qform->SetElement(0, 3, 100);
    qform->SetElement(1, 3, 120);
    qform->SetElement(2, 3, -30);
    vtkNew<vtkNIFTIImageWriter> nifti;
    nifti->SetInputConnection(mhd->GetOutputPort());
    nifti->SetQFormMatrix(qform);
    const std::string path = (scratch() / (flip < 0 ? "lps.nii" : "ras.nii")).string();
    nifti->SetFileName(path.c_str());
    nifti->Write();
    const CtVolume ct = read_ct_volume(path);
    // World = qform applied to the image's points: VTK's writer folds the image's origin (10, 20, 30) into the
    // qform's offset, which the file then holds (flip -1: qoffset (90, 100, 0)).
    expect_voxels_at_their_scan_points(ct, [flip](int i, int j, int k) {
      const Eigen::Vector3d ras(100 + flip * (10 + 0.5 * i), 120 + flip * (20 + j), -30 + 30 + 2 * k);
      return Eigen::Vector3d(-ras.x(), -ras.y(), ras.z());
    });
    EXPECT_TRUE(ct.scan_frame.left_at_minus_x()) << path;
    if (flip < 0) continue;
    // The same file with qfac -1 (pixdim[0], as FSL's radiological files have it): its slices run downwards from the
    // offset, world (110 + 0.5 i, 140 + j, -2 k); VTK's reader reverses them, the frame follows.
    std::string bytes;
    {
      std::ifstream in(path, std::ios::binary);
      bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    const float qfac = -1;
    std::memcpy(&bytes[76], &qfac, sizeof qfac);
    const std::string reversed = (scratch() / "qfac.nii").string();
    std::ofstream(reversed, std::ios::binary) << bytes;
    const CtVolume down = read_ct_volume(reversed);
    expect_voxels_at_their_scan_points(
        down, [](int i, int j, int k) { return Eigen::Vector3d(-(110 + 0.5 * i), -(140 + j), -2.0 * k); });
    EXPECT_TRUE(down.scan_frame.left_at_minus_x());
  }
}

// A NRRD file says its space: RAS is turned into LPS, LPS (or none) taken as it is.
TEST(CtVolume, ANrrdFilesSpaceSaysWhereItsVoxelsLie) {
  int files = 0;
  for (const std::string space : {"right-anterior-superior", "RAS", "left-posterior-superior", ""}) {
    const std::string path = (scratch() / ("space" + std::to_string(++files) + ".nrrd")).string();
    std::filesystem::create_directories(scratch());
    std::ofstream out(path, std::ios::binary);
    out << "NRRD0004\ntype: short\ndimension: 3\nsizes: 10 4 5\nencoding: raw\nendian: little\n";
    if (!space.empty())
      out << "space: " << space << "\nspace directions: (0.5,0,0) (0,1,0) (0,0,2)\nspace origin: (10,20,30)\n";
    else
      out << "spacings: 0.5 1 2\n";
    out << "\n";
    for (int k = 0; k < 5; ++k)
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 10; ++i) {
          const std::int16_t v = static_cast<std::int16_t>(i + 10 * j + 100 * k);
          out.write(reinterpret_cast<const char*>(&v), sizeof v);
        }
    out.close();
    const CtVolume ct = read_ct_volume(path);
    const double sign = space.rfind("right", 0) == 0 || space == "RAS" ? -1 : 1;
    const Eigen::Vector3d origin = space.empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(10, 20, 30);
    expect_voxels_at_their_scan_points(ct, [&](int i, int j, int k) {
      const Eigen::Vector3d p = origin + Eigen::Vector3d(0.5 * i, j, 2 * k);
      return Eigen::Vector3d(sign * p.x(), sign * p.y(), p.z());
    });
    EXPECT_EQ(ct.scan_frame.left_at_minus_x(), sign < 0) << space;
  }
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
