// NIfTI-1 files whose header does not match their data, or that would be read with an axis silently flipped, are
// refused naming the file; the orientation of a sound one is applied.
#include "core/segment/nifti_header.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/segment/ct_volume.h"
#include "core/util/error.h"
#include "tests/core/io/io_test_util.h"

namespace facehex {
namespace {

namespace fs = std::filesystem;

// A 4 x 5 x 6 int16 volume whose voxel (i, j, k) is i + 10 j + 100 k, spacing 1 x 2 x 3 mm, as a .nii file; `edit`
// changes the header (byte offsets of the NIfTI-1 standard) before it is written, `extra` bytes follow the voxels.
struct NiftiFile {
  std::vector<char> header = std::vector<char>(352, 0);
  long extra = 0;
  NiftiFile() {
    set<std::int32_t>(0, 348);
    const std::int16_t dims[8] = {3, 4, 5, 6, 1, 1, 1, 1};
    for (int a = 0; a < 8; ++a) set<std::int16_t>(40 + 2 * a, dims[a]);
    set<std::int16_t>(70, 4);  // int16
    set<std::int16_t>(72, 16);
    const float pixdim[4] = {1, 1, 2, 3};
    for (int a = 0; a < 4; ++a) set<float>(76 + 4 * a, pixdim[a]);
    set<float>(108, 352);  // vox_offset
    set<float>(112, 1);    // scl_slope
    std::memcpy(&header[344], "n+1", 4);
  }
  template <class T>
  void set(int offset, T value) {
    std::memcpy(&header[offset], &value, sizeof value);
  }
  // An sform: voxel axis a points along columns[a] (RAS), spacing included.
  void sform(const float (&rows)[3][4]) {
    set<std::int16_t>(254, 1);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) set<float>(280 + 16 * r + 4 * c, rows[r][c]);
  }
  std::string write(const std::string& name) const {
    const std::string path = (test::program_scratch_dir() / name).string();
    std::ofstream out(path, std::ios::binary);
    out.write(header.data(), header.size());
    for (int k = 0; k < 6; ++k)
      for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 4; ++i) {
          const std::int16_t v = static_cast<std::int16_t>(i + 10 * j + 100 * k);
          out.write(reinterpret_cast<const char*>(&v), sizeof v);
        }
    for (long b = 0; b < extra; ++b) out.put(0);
    return path;
  }
};

void expect_refused(const NiftiFile& file, const std::string& name, const std::string& needle) {
  const std::string path = file.write(name);
  try {
    read_ct_volume(path);
    ADD_FAILURE() << name << " was read";
  } catch (const Error& e) {
    EXPECT_EQ(e.subject(), path);
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(NiftiHeader, ASoundFileReadsWithItsSizes) {
  const std::string path = NiftiFile().write("sound.nii");
  const NiftiHeader h = check_nifti_header(path);
  EXPECT_EQ(h.dims, (std::array<long long, 3>{4, 5, 6}));
  EXPECT_EQ(h.spacing, (std::array<double, 3>{1, 2, 3}));
  const CtVolume ct = read_ct_volume(path);
  EXPECT_EQ(ct.intensity(3, 4, 5), 543.0f);
}

TEST(NiftiHeader, SizesThatDoNotMatchTheDataAreRefused) {
  NiftiFile larger;
  larger.set<std::int16_t>(46, 7);  // dim[3]
  expect_refused(larger, "larger.nii", "the file holds 592");
  NiftiFile extra;
  extra.extra = 2;
  expect_refused(extra, "extra.nii", "the file holds more");
  NiftiFile time;
  time.set<std::int16_t>(40, 4), time.set<std::int16_t>(48, 2);  // 4-D, two time points
  expect_refused(time, "time.nii", "dim[4] is 2");
  NiftiFile type;
  type.set<std::int16_t>(72, 8);  // bitpix of another type
  expect_refused(type, "type.nii", "bitpix 8 does not match datatype 4");
  NiftiFile offset;
  offset.set<float>(108, 100);
  expect_refused(offset, "offset.nii", "vox_offset");
}

TEST(NiftiHeader, ZeroOrNegativeVoxelSizesAreRefused) {
  for (const float size : {0.0f, -2.0f}) {
    NiftiFile f;
    f.set<float>(84, size);  // pixdim[2]
    expect_refused(f, "spacing.nii", "pixdim[2]");
  }
}

// An sform with the second voxel axis pointing posterior: the volume is read with anterior +y, each voxel where the
// sform puts it (x right, z superior as stored); an oblique sform is refused unless the axes are given.
TEST(NiftiHeader, TheOrientationIsAppliedAndAnObliqueOneRefused) {
  NiftiFile posterior;
  posterior.sform({{1, 0, 0, 0}, {0, -2, 0, 0}, {0, 0, 3, 0}});
  const CtVolume ct = read_ct_volume(posterior.write("posterior.nii"));
  EXPECT_EQ(ct.intensity(0, 0, 0), 40.0f);   // stored voxel (0, 4, 0), the most posterior row
  EXPECT_EQ(ct.intensity(3, 4, 5), 503.0f);  // stored voxel (3, 0, 5), the most anterior row
  EXPECT_EQ(read_ct_volume(NiftiFile().write("stored.nii")).intensity(0, 0, 0), 0.0f);

  NiftiFile oblique;
  oblique.sform({{0.7071f, -1.4142f, 0, 0}, {0.7071f, 1.4142f, 0, 0}, {0, 0, 3, 0}});
  expect_refused(oblique, "oblique.nii", "oblique");
  const CtVolume given = read_ct_volume(oblique.write("oblique.nii"), {"+y", "+z"});
  EXPECT_EQ(given.intensity(3, 4, 5), 543.0f);
}

}  // namespace
}  // namespace facehex
