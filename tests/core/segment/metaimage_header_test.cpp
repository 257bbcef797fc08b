// A MetaImage header that does not match its data, or whose axes the reader would silently get wrong, is refused
// before VTK reads it, with the field at fault named; a good one reads, through the header check, as before.
#include "core/segment/metaimage_header.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>

#include "core/segment/ct_volume.h"
#include "core/util/error.h"

namespace facehex {
namespace {

namespace fs = std::filesystem;

class MetaImageHeaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("facehex_mhd_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    std::ofstream raw(dir_ / "v.raw", std::ios::binary);
    for (int i = 0; i < 4 * 5 * 6; ++i) {
      const std::int16_t v = static_cast<std::int16_t>(i % 7 * 100);
      raw.write(reinterpret_cast<const char*>(&v), sizeof v);
    }
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The header with `field` (a whole "Key = Value" line) replacing its line of that key, or added.
  std::string header(const std::string& replace_key = "", const std::string& line = "") {
    std::string text;
    for (const std::string& l :
         {std::string("ObjectType = Image"), std::string("NDims = 3"), std::string("BinaryData = True"),
          std::string("ElementSpacing = 1 1.5 2"), std::string("TransformMatrix = 1 0 0 0 1 0 0 0 1"),
          std::string("DimSize = 4 5 6"), std::string("ElementType = MET_SHORT")}) {
      text += (!replace_key.empty() && l.rfind(replace_key + " ", 0) == 0 ? line : l) + "\n";
    }
    if (!replace_key.empty() && text.find(line) == std::string::npos) text += line + "\n";
    const std::string path = (dir_ / ("h" + std::to_string(count_++) + ".mhd")).string();
    std::ofstream(path) << text << "ElementDataFile = v.raw\n";
    return path;
  }

  std::string error_of(const std::string& path) {
    try {
      check_metaimage_header(path);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
  int count_ = 0;
};

TEST_F(MetaImageHeaderTest, AGoodHeaderPassesAndItsVolumeReads) {
  const std::string path = header();
  const MetaImageHeader h = check_metaimage_header(path);
  EXPECT_EQ(h.dims, (std::array<long long, 3>{4, 5, 6}));
  const CtVolume ct = read_ct_volume(path);
  EXPECT_EQ(ct.intensity.geometry.dims, (std::array<int, 3>{4, 5, 6}));
  EXPECT_EQ(ct.intensity.data.size(), 120u);
  EXPECT_EQ(ct.intensity.data[8], 100.0f);  // voxel 8 of the file, (0, 2, 0): kept in place by the +y/+z frame
}

TEST_F(MetaImageHeaderTest, EachBadFieldIsNamed) {
  const std::vector<std::pair<std::pair<std::string, std::string>, std::string>> cases = {
      {{"NDims", "NDims = -1"}, "NDims is '-1'"},
      {{"NDims", "NDims = 2147483648"}, "NDims is '2147483648'"},
      {{"DimSize", "DimSize = 4 5 7"}, "needs 280 bytes of data, the file holds 240"},
      {{"DimSize", "DimSize = 4 5 5"}, "needs 200 bytes of data, the file holds 240"},
      {{"DimSize", "DimSize = 4 5"}, "DimSize must hold 3 numbers"},
      {{"DimSize", "DimSize = 4 -5 6"}, "must be three whole numbers"},
      {{"ElementSpacing", "ElementSpacing = -1 1.5 2"}, "ElementSpacing '-1 1.5 2' must be positive"},
      {{"ElementSpacing", "ElementSpacing = 1 nan 2"}, "ElementSpacing"},
      {{"TransformMatrix", "TransformMatrix = -1 0 0 0 1 0 0 0 1"}, "is not the identity"},
      {{"ElementType", "ElementType = MET_STRING"}, "ElementType 'MET_STRING'"},
      {{"ElementNumberOfChannels", "ElementNumberOfChannels = 2.5"}, "ElementNumberOfChannels must be a whole number"},
      {{"ElementNumberOfChannels", "ElementNumberOfChannels = x"}, "ElementNumberOfChannels must hold 1 numbers"},
  };
  for (const auto& [edit, needle] : cases) {
    const std::string path = header(edit.first, edit.second);
    const std::string e = error_of(path);
    EXPECT_EQ(e.rfind(path + ": ", 0), 0u) << edit.second << " -> " << e;
    EXPECT_NE(e.find(needle), std::string::npos) << edit.second << " -> " << e;
  }
}

TEST_F(MetaImageHeaderTest, ATruncatedDataFileIsRefused) {
  const std::string path = header();
  fs::resize_file(dir_ / "v.raw", 200);
  EXPECT_NE(error_of(path).find("the file holds 200"), std::string::npos) << error_of(path);
  fs::remove(dir_ / "v.raw");
  EXPECT_NE(error_of(path).find("cannot be read"), std::string::npos) << error_of(path);
}

TEST_F(MetaImageHeaderTest, CompressedDataMustHaveItsDeclaredSize) {
  const std::string path = (dir_ / "c.mha").string();
  std::ofstream(path) << "ObjectType = Image\nNDims = 3\nDimSize = 4 4 4\nElementType = MET_SHORT\n"
                         "CompressedData = True\nCompressedDataSize = 100\nElementDataFile = LOCAL\n0123456789";
  EXPECT_NE(error_of(path).find("CompressedDataSize 100 does not match the 10 bytes"), std::string::npos)
      << error_of(path);
}

TEST_F(MetaImageHeaderTest, TextThatIsNotAHeaderIsRefused) {
  const std::string path = (dir_ / "text.mhd").string();
  std::ofstream(path) << "this is not\na header\n";
  EXPECT_NE(error_of(path).find("not a MetaImage header"), std::string::npos) << error_of(path);
}

}  // namespace
}  // namespace facehex
