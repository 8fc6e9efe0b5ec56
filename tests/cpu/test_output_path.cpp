// Output paths checked before the work (base/output_path.hpp): only regular files are replaced,
// the directory must take a new file, nothing is left behind, and one file has one identity.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <stdexcept>

#include "nimbus/base/output_path.hpp"
#include "support/vdb_fixtures.hpp"

namespace nimbus::test {
namespace {

namespace fs = std::filesystem;

std::string error_of(const fs::path& p) {
  try {
    check_output_path(p, "-o");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

std::size_t entries(const fs::path& dir) {
  std::size_t n = 0;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator(); ++it) ++n;
  return n;
}

TEST(OutputPath, WritablePlacesPassAndLeaveNothing) {
  TempDir d;
  write_bytes(d / "old.exr", "x");
  EXPECT_EQ(error_of(d / "new.exr"), "");
  EXPECT_EQ(error_of(d / "old.exr"), "");
  EXPECT_EQ(error_of(d / "a" / "b" / "new.exr"), "");  // directories that can be made
  EXPECT_EQ(entries(d.path), 1u);
  EXPECT_FALSE(fs::exists(d / "a"));
}

TEST(OutputPath, NonRegularFilesAndUnwritablePlacesAreRefused) {
  TempDir d;
  write_bytes(d / "file", "x");
  fs::create_directories(d / "dir");
  ::mkfifo((d / "fifo").c_str(), 0600);
  fs::create_symlink(d / "file", d / "link.exr");
  EXPECT_NE(error_of(d / "dir").find("is a directory"), std::string::npos);
  EXPECT_NE(error_of(d / "fifo").find("is a FIFO"), std::string::npos);
  EXPECT_NE(error_of(d / "link.exr").find("is a symbolic link"), std::string::npos);
  EXPECT_NE(error_of("/dev/null").find("is a character device"), std::string::npos);
  EXPECT_NE(error_of(d / "file" / "x.exr").find("is not a directory"), std::string::npos);
  EXPECT_NE(error_of(d / "file" / "deeper" / "x.exr").find("is not a directory"), std::string::npos);
  // /proc takes no new files, even from root, whose permission bits are never in the way.
  EXPECT_NE(error_of("/proc/nimbus_cannot_write_here.exr").find("cannot be written"), std::string::npos);
  // A name one byte short of the limit leaves no room for the temporary's name beside it.
  EXPECT_NE(error_of(d / std::string(250, 'n')).find("cannot be written"), std::string::npos);
  EXPECT_EQ(entries(d.path), 4u) << "nothing left behind";
}

TEST(OutputPath, OneFileHasOneIdentityHoweverItIsNamed) {
  TempDir d;
  write_bytes(d / "a.json", "x");
  fs::create_directories(d / "sub");
  fs::create_hard_link(d / "a.json", d / "hard.json");
  EXPECT_EQ(file_identity(d / "a.json"), file_identity(d / "sub" / ".." / "a.json"));
  EXPECT_EQ(file_identity(d / "a.json"), file_identity(d / "hard.json"));
  EXPECT_NE(file_identity(d / "a.json"), file_identity(d / "b.json"));
  EXPECT_EQ(file_identity(d / "b.json"), file_identity(d / "sub" / ".." / "b.json"));  // neither exists
  EXPECT_NE(file_identity(d / "b.json"), file_identity(d / "sub" / "b.json"));
}

}  // namespace
}  // namespace nimbus::test
