// Output paths checked before the work (base/output_path.hpp): only regular files are replaced,
// the directory must take a new file, nothing is left behind, and one file has one identity.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "nimbus/base/atomic_file.hpp"
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

// Two threads checking one output path at once: the probe was named by the pid alone, so one
// thread's probe made the other's creation fail ("cannot be written (File exists)"). Each probe
// is now unique to its call.
TEST(OutputPath, ConcurrentChecksOfOnePathNeverCollide) {
  TempDir d;
  std::atomic<int> failures{0};
  std::string first_failure;
  std::atomic<bool> noted{false};
  const auto hammer = [&] {
    for (int i = 0; i < 3000; ++i) {
      const std::string e = error_of(d / "o.exr");
      if (e.empty()) continue;
      if (!noted.exchange(true)) first_failure = e;
      ++failures;
    }
  };
  std::thread a(hammer), b(hammer);
  a.join();
  b.join();
  EXPECT_EQ(failures.load(), 0) << first_failure;
  EXPECT_EQ(entries(d.path), 0u) << "no probe left behind";
}

// A probe left by a process that died between creating and removing it (its name was
// ".NAME.tmp<pid>.probe", and pids come round again) made every later check of that path fail.
TEST(OutputPath, ALeftoverProbeOfAnyNameDoesNotMatter) {
  TempDir d;
  write_bytes(d / (".o.exr.tmp" + std::to_string(::getpid()) + ".probe"), "");
  fs::create_directories(d / (".nimbus-probe" + std::to_string(::getpid())));
  EXPECT_EQ(error_of(d / "o.exr"), "");
  EXPECT_EQ(error_of(d / "new" / "o.exr"), "");  // a missing folder: the probe folder beside it
  EXPECT_EQ(entries(d.path), 2u);
}

// write_atomically's temporary was ".NAME.tmp<pid>.<counter>", a name anyone could foresee and
// plant a symbolic link at, through which the write then went. The temporary is now created
// with O_EXCL under an unforeseeable name: planted files are never opened, let alone written.
TEST(AtomicFile, FilesPlantedAtTheTemporarysNameAreNeverWrittenThrough) {
  TempDir d;
  write_bytes(d / "victim", "untouched");
  for (int counter = 0; counter < 200; ++counter)
    fs::create_symlink(d / "victim", d / (".out.json.tmp" + std::to_string(::getpid()) + "." + std::to_string(counter)));
  for (int i = 0; i < 20; ++i)
    write_atomically(d / "out.json", [&](const fs::path& tmp) { write_bytes(tmp, "written " + std::to_string(i)); });
  EXPECT_EQ(read_bytes(d / "victim"), "untouched");
  EXPECT_EQ(read_bytes(d / "out.json"), "written 19");
  EXPECT_EQ(entries(d.path), 202u) << "no temporary left behind";
}

// Temporaries of one target, drawn at once from many threads, are all different files.
TEST(AtomicFile, TemporariesOfOneTargetAreDistinctAcrossThreads) {
  TempDir d;
  std::vector<std::vector<fs::path>> made(4);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < made.size(); ++t)
    threads.emplace_back([&, t] {
      for (int i = 0; i < 200; ++i) made[t].push_back(create_file_beside(d / "o.vdb"));
    });
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(entries(d.path), 800u);
  for (const auto& list : made)
    for (const fs::path& p : list) EXPECT_EQ(p.parent_path(), d.path);
}

}  // namespace
}  // namespace nimbus::test
