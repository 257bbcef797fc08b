// NRRD files whose header does not match their raw data, or whose directions the reader would ignore, are refused
// naming the file.
#include "core/segment/nrrd_header.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/segment/ct_volume.h"
#include "core/util/error.h"
#include "tests/core/io/io_test_util.h"

namespace facehex {
namespace {

namespace fs = std::filesystem;

// A 12 x 5 x 6 int16 volume whose voxel (i, j, k) is i + 100 j + 1000 k, attached raw data after `fields`.
std::string write_nrrd(const std::string& name, const std::string& fields, int voxels = 360,
                       const std::string& sizes = "12 5 6") {
  const std::string path = (test::program_scratch_dir() / name).string();
  std::ofstream out(path, std::ios::binary);
  out << "NRRD0004\n# a test volume\ntype: short\ndimension: 3\nsizes: " << sizes << "\nendian: little\nencoding: raw\n"
      << fields << "\n";
  for (int v = 0; v < voxels; ++v) {
    const std::int16_t value = static_cast<std::int16_t>(v % 12 + 100 * (v / 12 % 5) + 1000 * (v / 60));
    out.write(reinterpret_cast<const char*>(&value), sizeof value);
  }
  return path;
}

void expect_refused(const std::string& path, const std::string& needle) {
  try {
    read_ct_volume(path);
    ADD_FAILURE() << path << " was read";
  } catch (const Error& e) {
    EXPECT_EQ(e.subject(), path);
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(NrrdHeader, ASoundFileReads) {
  for (const char* fields : {"spacings: 1 2 3\n",
                             "space: left-posterior-superior\n"
                             "space directions: (1,0,0) (0,2,0) (0,0,3)\n"}) {
    const CtVolume ct = read_ct_volume(write_nrrd("sound.nrrd", fields));
    EXPECT_EQ(ct.intensity.geometry.dims, (std::array<int, 3>{12, 5, 6}));
    EXPECT_TRUE(ct.intensity.geometry.spacing.isApprox(Eigen::Vector3d(1, 2, 3))) << fields;
    EXPECT_EQ(ct.intensity(11, 4, 5), 5411.0f);
  }
}

// VTK's reader loops for its whole time limit on a magic line with bytes after the version (a fuzzer's find).
TEST(NrrdHeader, OnlyTheFiveMagicLinesAreTaken) {
  const std::string sound = write_nrrd("magic.nrrd", "");
  std::ifstream in(sound, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string rest = bytes.substr(bytes.find('\n'));
  for (const std::string& magic : {std::string("NRRD000\x01\x00"
                                               "4",
                                               10),
                                   std::string("NRRD0009"), std::string("NRRD00041"), std::string("NRRD0004 ")}) {
    const std::string path = sound + ".bad.nrrd";
    std::ofstream(path, std::ios::binary) << magic << rest;
    expect_refused(path, "the NRRD magic line is not NRRD0001 to NRRD0005");
  }
  std::ofstream(sound + ".crlf.nrrd", std::ios::binary) << "NRRD0004\r" << rest;
  EXPECT_EQ(read_ct_volume(sound + ".crlf.nrrd").intensity.geometry.dims, (std::array<int, 3>{12, 5, 6}));
}

// VTK's reader can loop on a damaged list of data files (a fuzzer's find); a CT comes as one file.
TEST(NrrdHeader, DataSplitOverSeveralFilesAreRefused) {
  expect_refused(write_nrrd("list.nrrd", "data file: LIST\n"), "its data are split over several files");
  expect_refused(write_nrrd("numbered.nrrd", "data file: slice%03d.raw 1 8 1\n"), "join them into one NRRD file");
}

TEST(NrrdHeader, SizesThatDoNotMatchTheDataAreRefused) {
  expect_refused(write_nrrd("short.nrrd", "", 359), "need 720 bytes of raw data, the file holds 718");
  expect_refused(write_nrrd("long.nrrd", "", 361), "the file holds 722");
  // VTK would read 4 x 5 x 6 as a 5 x 6 image of 4 components.
  expect_refused(write_nrrd("narrow.nrrd", "", 120, "4 5 6"), "a first axis of fewer than 10 samples");
}

TEST(NrrdHeader, DirectionsAndSpacingsTheReaderWouldIgnoreAreRefused) {
  expect_refused(write_nrrd("flip.nrrd", "space directions: (-1,0,0) (0,2,0) (0,0,3)\n"), "space directions");
  expect_refused(write_nrrd("turn.nrrd", "space directions: (0,1,0) (2,0,0) (0,0,3)\n"), "space directions");
  expect_refused(write_nrrd("zero.nrrd", "spacings: 1 0 3\n"), "spacings");
}

}  // namespace
}  // namespace facehex
