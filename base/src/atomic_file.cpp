// Temporary-file-then-rename writes.
#include "nimbus/base/atomic_file.hpp"

#include <fcntl.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <system_error>

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

// 64 bits from the kernel's random source; should it fail, the clock's nanoseconds and a stack
// address (the pid, thread and counter of the name still set the calls of this host apart).
uint64_t random_bits() {
  uint64_t r = 0;
  if (::getrandom(&r, sizeof r, GRND_NONBLOCK) == static_cast<ssize_t>(sizeof r)) return r;
  const auto now = static_cast<uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
  return now ^ (reinterpret_cast<std::uintptr_t>(&r) << 16);
}

}  // namespace

std::filesystem::path unique_name_beside(const std::filesystem::path& path, const std::string& tag) {
  static std::atomic<uint64_t> counter{0};
  const std::filesystem::path parent = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  char suffix[96];
  std::snprintf(suffix, sizeof suffix, "%ld.%ld.%llu.%016llx", static_cast<long>(::getpid()), static_cast<long>(::gettid()),
                static_cast<unsigned long long>(counter++), static_cast<unsigned long long>(random_bits()));
  return parent / ("." + path.filename().string() + tag + suffix);
}

std::filesystem::path create_file_beside(const std::filesystem::path& path, const std::string& tag) {
  for (int attempt = 0;; ++attempt) {
    std::filesystem::path name = unique_name_beside(path, tag);
    const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      ::close(fd);
      return name;
    }
    // Another file holds the name (a leftover, or a file made to block this one): draw again.
    // A hundred clashes in a row are no accident of chance but a folder that fails every name.
    if (errno != EEXIST || attempt == 100) {
      const std::filesystem::path parent = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
      throw std::system_error(errno, std::generic_category(), parent.string());
    }
  }
}

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
  // The temporary is ours alone: created here with O_EXCL under a name no other writer draws,
  // then filled by `write`.
  fs::path tmp;
  try {
    tmp = create_file_beside(path);
  } catch (const std::system_error& e) {
    throw std::runtime_error("cannot write '" + echo(path.string(), 200) + "': " + e.code().message());
  }
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
