#include "core/util/atomic_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include "tests/core/io/io_test_util.h"

namespace facehex {
namespace {

using test::TempDir;
namespace fs = std::filesystem;

TEST(AtomicFile, WritesThroughATemporaryFileBesideTheTarget) {
  TempDir dir;
  const std::string target = dir.file("mesh.vtu");
  std::string seen_tmp;
  write_atomically(target, [&](const std::string& tmp) {
    seen_tmp = tmp;
    EXPECT_FALSE(fs::exists(target)) << "target must not appear before the writer is done";
    test::write_file(tmp, "content");
  });
  EXPECT_EQ(test::read_file(target), "content");
  EXPECT_EQ(fs::path(seen_tmp).parent_path(), dir.path());
  const std::string tmp_name = fs::path(seen_tmp).filename().string();
  EXPECT_EQ(tmp_name.rfind(".mesh.tmp", 0), 0u) << seen_tmp;
  EXPECT_EQ(fs::path(seen_tmp).extension(), ".vtu") << "writers may insist on the extension";
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"mesh.vtu"});
}

TEST(AtomicFile, ReplacedFileGetsTheUsualPermissions) {
  TempDir dir;
  const std::string target = dir.file("a.txt");
  const mode_t old_mask = ::umask(022);
  write_atomically(target, [](const std::string& tmp) { test::write_file(tmp, "x"); });
  ::umask(old_mask);
  struct stat st {};
  ASSERT_EQ(::stat(target.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0644u);
}

TEST(AtomicFile, FailingWriterLeavesNoFileAndNoTemporary) {
  TempDir dir;
  const std::string target = dir.file("out.msh");
  test::expect_error(
      [&] {
        write_atomically(target, [](const std::string& tmp) {
          test::write_file(tmp, "half a mesh");
          throw std::runtime_error("disk on fire");
        });
      },
      target + ": disk on fire");
  EXPECT_TRUE(dir.entries().empty());
}

TEST(AtomicFile, FailingWriterKeepsTheOldTarget) {
  TempDir dir;
  const std::string target = dir.file("out.msh");
  test::write_file(target, "old content");
  EXPECT_THROW(write_atomically(target,
                                [](const std::string& tmp) {
                                  test::write_file(tmp, "new");
                                  throw Error(tmp, "cannot convert");
                                }),
               Error);
  EXPECT_EQ(test::read_file(target), "old content");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.msh"});
}

TEST(AtomicFile, ErrorsAboutTheTemporaryFileNameTheTarget) {
  TempDir dir;
  const std::string target = dir.file("out.vtu");
  try {
    write_atomically(target, [](const std::string& tmp) { throw Error(tmp, "cannot write to " + tmp); });
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), target + ": cannot write to " + target);
    EXPECT_EQ(e.subject(), target);
  }
}

TEST(AtomicFile, WriterThatProducesNothingIsAnError) {
  TempDir dir;
  const std::string target = dir.file("out.vtu");
  test::expect_error([&] { write_atomically(target, [](const std::string&) {}); }, "no file was produced");
  EXPECT_TRUE(dir.entries().empty());
}

TEST(AtomicFile, MissingFolderIsReportedBeforeWriting) {
  TempDir dir;
  const std::string target = dir.file("no/such/folder/out.vtu");
  bool called = false;
  test::expect_error([&] { write_atomically(target, [&](const std::string&) { called = true; }); },
                     "folder '" + dir.file("no/such/folder") + "' does not exist");
  EXPECT_FALSE(called);
}

TEST(AtomicFile, FolderInsteadOfFileIsReported) {
  TempDir dir;
  fs::create_directory(dir.file("out.vtu"));
  test::expect_error([&] { write_atomically(dir.file("out.vtu"), [](const std::string&) {}); }, "a folder");
}

TEST(AtomicFile, ReadOnlyFolderIsReported) {
  if (::geteuid() == 0) GTEST_SKIP() << "root may write anywhere";
  TempDir dir;
  fs::permissions(dir.path(), fs::perms::owner_read | fs::perms::owner_exec);
  test::expect_error([&] { write_atomically(dir.file("out.vtu"), [](const std::string&) {}); }, "not writable");
  fs::permissions(dir.path(), fs::perms::owner_all);
}

}  // namespace
}  // namespace facehex
