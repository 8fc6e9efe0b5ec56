// Output-path checks before the work (output_path.hpp).
#include "nimbus/base/output_path.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "nimbus/base/file_kind.hpp"

namespace nimbus {
namespace {

namespace fs = std::filesystem;

std::string error_text(int e) { return std::strerror(e); }

}  // namespace

void check_output_path(const fs::path& path, const std::string& what) {
  const std::string where = what + " '" + path.string() + "'";
  if (path.empty()) throw std::runtime_error(what + ": the file name is empty");
  if (!path.has_filename()) throw std::runtime_error(where + ": names a directory, not a file");
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    throw std::runtime_error(where + ": is " + file_kind(st.st_mode) + "; only a regular file is replaced");
  const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (::stat(parent.c_str(), &st) == 0) {
    if (!S_ISDIR(st.st_mode)) throw std::runtime_error(where + ": " + parent.string() + " is not a directory");
    // The same name pattern as write_atomically's temporary, so a name too long for it fails here.
    const fs::path probe = parent / ("." + path.filename().string() + ".tmp" + std::to_string(::getpid()) + ".probe");
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) throw std::runtime_error(where + ": cannot be written (" + error_text(errno) + ")");
    ::close(fd);
    ::unlink(probe.c_str());
    return;
  }
  // The parent is missing: its nearest existing ancestor must be a directory that takes a new one.
  fs::path ancestor = parent;
  while (::stat(ancestor.c_str(), &st) != 0) {
    if (errno != ENOENT && errno != ENOTDIR) throw std::runtime_error(where + ": cannot reach " + ancestor.string() + " (" + error_text(errno) + ")");
    if (!ancestor.has_parent_path() || ancestor.parent_path() == ancestor) {
      ancestor = ".";
      if (::stat(ancestor.c_str(), &st) != 0) throw std::runtime_error(where + ": cannot reach the current directory");
      break;
    }
    ancestor = ancestor.parent_path();
  }
  if (!S_ISDIR(st.st_mode))
    throw std::runtime_error(where + ": cannot create its directory, " + ancestor.string() + " is not a directory");
  const fs::path probe = ancestor / (".nimbus-probe" + std::to_string(::getpid()));
  if (::mkdir(probe.c_str(), 0700) != 0)
    throw std::runtime_error(where + ": cannot create its directory in " + ancestor.string() + " (" + error_text(errno) + ")");
  ::rmdir(probe.c_str());
}

std::string file_identity(const fs::path& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0)
    return "inode " + std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
  std::error_code ec;
  fs::path p = fs::absolute(path, ec);
  if (ec) p = path;
  const fs::path c = fs::weakly_canonical(p, ec);
  return "path " + (ec ? p.lexically_normal() : c).string();
}

}  // namespace nimbus
