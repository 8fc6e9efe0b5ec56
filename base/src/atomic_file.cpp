// Temporary-file-then-rename writes.
#include "nimbus/base/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <stdexcept>
#include <string>

#include "nimbus/base/file_kind.hpp"
#include "nimbus/base/input_limits.hpp"

namespace nimbus {
namespace {

// Flushes a file's (or directory's) data to the disk, so that after a crash the renamed file
// holds the complete content rather than an empty or partial one.
bool sync_path(const std::filesystem::path& p, int flags) {
  const int fd = ::open(p.c_str(), flags | O_CLOEXEC);
  if (fd < 0) return false;
  const bool ok = ::fsync(fd) == 0;
  ::close(fd);
  return ok;
}

}  // namespace

void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path&)>& write) {
  namespace fs = std::filesystem;
  if (path.empty()) throw std::invalid_argument("output path is empty");
  const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) throw std::runtime_error("cannot create directory " + parent.string() + ": " + ec.message());
  // Only a regular file is ever replaced: renaming over a symbolic link, FIFO or device would
  // put a file in its place (as root, /dev/null itself), and a directory cannot be.
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    throw std::runtime_error("'" + echo(path.string(), 200) + "' is " + file_kind(st.st_mode) + ", not a regular file: not replaced");
  static std::atomic<unsigned> counter{0};
  const fs::path tmp = parent / ("." + path.filename().string() + ".tmp" +
                                 std::to_string(::getpid()) + "." + std::to_string(counter++));
  try {
    write(tmp);
    if (!sync_path(tmp, O_RDONLY)) throw std::runtime_error("cannot flush " + path.string() + " to disk");
    fs::rename(tmp, path);
    sync_path(parent, O_RDONLY | O_DIRECTORY);  // makes the rename durable; best effort
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
}

}  // namespace nimbus
