// The fuzz harness in the normal test suite (docs/robustness.md): every reader reads its seeds, so the harness feeds
// the readers what it means to, and every input the fuzzers found (regressions/READER/) is refused with an error
// naming the file.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

#include "tests/fuzz/fuzz_readers.h"

namespace facehex::fuzz {
namespace {

namespace fs = std::filesystem;

class FuzzInputs : public ::testing::Test {
 protected:
  FuzzInputs() {
    std::string pattern = (fs::temp_directory_path() / "facehex_fuzz_test_XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
    dir_ = pattern;
  }
  ~FuzzInputs() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  // Runs `check(reader, file, bytes)` on every file of FACEHEX_FUZZ_DIR/<folder>/<reader>/; returns how many.
  template <class Check>
  int for_each_input(const std::string& folder, const Check& check) const {
    int count = 0;
    for (const std::string& reader : reader_names()) {
      const fs::path inputs = fs::path(FACEHEX_FUZZ_DIR) / folder / reader;
      if (!fs::is_directory(inputs)) continue;
      for (const auto& entry : fs::directory_iterator(inputs)) {
        std::ifstream in(entry.path(), std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        check(reader, entry.path().filename().string(), bytes);
        ++count;
      }
    }
    return count;
  }

  static const std::uint8_t* data(const std::string& bytes) {
    return reinterpret_cast<const std::uint8_t*>(bytes.data());
  }

  std::string dir_;
};

TEST_F(FuzzInputs, EveryReaderReadsItsSeeds) {
  std::set<std::string> seeded;
  for_each_input("corpus", [&](const std::string& reader, const std::string& file, const std::string& bytes) {
    seeded.insert(reader);
    const std::optional<std::string> refusal = read_input(reader, data(bytes), bytes.size(), dir_);
    EXPECT_FALSE(refusal) << reader << " seed " << file << ": " << *refusal;
  });
  EXPECT_EQ(seeded, std::set<std::string>(reader_names().begin(), reader_names().end()));
}

TEST_F(FuzzInputs, FoundInputsAreRefusedNamingTheFile) {
  const int found =
      for_each_input("regressions", [&](const std::string& reader, const std::string& file, const std::string& bytes) {
        const std::optional<std::string> refusal = read_input(reader, data(bytes), bytes.size(), dir_);
        ASSERT_TRUE(refusal) << reader << " " << file << " was read";
        EXPECT_NE(refusal->find(input_path(reader, data(bytes), bytes.size(), dir_)), std::string::npos)
            << reader << " " << file << ": " << *refusal;
      });
  EXPECT_GT(found, 0);
}

}  // namespace
}  // namespace facehex::fuzz
