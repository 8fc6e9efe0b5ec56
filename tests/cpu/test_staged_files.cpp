// Several files as one result (base/staged_files.hpp): all are written, or none is, and what
// was there before stays.
#include <gtest/gtest.h>

#include <stdexcept>

#include "nimbus/base/staged_files.hpp"
#include "support/vdb_fixtures.hpp"

namespace nimbus::test {
namespace {

namespace fs = std::filesystem;

auto content(const std::string& text) {
  return [text](const fs::path& tmp) { write_bytes(tmp, text); };
}

TEST(StagedFiles, CommitWritesEveryFile) {
  TempDir d;
  write_bytes(d / "a.exr", "old a");
  {
    StagedFiles files;
    files.write(d / "a.exr", content("new a"));
    files.write(d / "sub" / "b.png", content("new b"));
    EXPECT_EQ(read_bytes(d / "a.exr"), "old a") << "nothing replaced before the commit";
    EXPECT_FALSE(fs::exists(d / "sub" / "b.png"));
    files.commit();
  }
  EXPECT_EQ(read_bytes(d / "a.exr"), "new a");
  EXPECT_EQ(read_bytes(d / "sub" / "b.png"), "new b");
  EXPECT_EQ(count_temp_files(d.path) + count_temp_files(d / "sub"), 0);
}

TEST(StagedFiles, AFailedWriteLeavesNoFileAndNamesTheTarget) {
  TempDir d;
  write_bytes(d / "b.png", "old b");
  try {
    StagedFiles files;
    files.write(d / "a.exr", content("new a"));
    files.write(d / "b.png", [](const fs::path& tmp) {
      write_bytes(tmp, "half");
      throw std::runtime_error("cannot write PNG " + tmp.string() + ": disk full");
    });
    ADD_FAILURE() << "the failed write did not throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write PNG " + (d / "b.png").string() + ": disk full"), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(d / "a.exr"));
  EXPECT_EQ(read_bytes(d / "b.png"), "old b");
  EXPECT_EQ(count_temp_files(d.path), 0);
}

TEST(StagedFiles, AFailedRenamePutsBackTheFilesRenamedBeforeIt) {
  TempDir d;
  write_bytes(d / "a.exr", "old a");
  StagedFiles files;
  files.write(d / "a.exr", content("new a"));
  files.write(d / "new.exr", content("new"));
  files.write(d / "b.png", content("new b"));
  // b.png becomes a directory that is not empty, which no rename can replace.
  fs::create_directories(d / "b.png" / "inside");
  EXPECT_THROW(files.commit(), std::runtime_error);
  EXPECT_EQ(read_bytes(d / "a.exr"), "old a");
  EXPECT_FALSE(fs::exists(d / "new.exr"));
  EXPECT_TRUE(fs::is_directory(d / "b.png" / "inside"));
  int left = 0;
  for (const auto& e : fs::directory_iterator(d.path)) left += e.path().filename().string()[0] == '.';
  EXPECT_EQ(left, 0) << "temporaries or backups left behind";
}

}  // namespace
}  // namespace nimbus::test
