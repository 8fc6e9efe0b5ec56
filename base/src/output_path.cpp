// Output-path checks before the work (output_path.hpp).
#include "nimbus/base/output_path.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>

#include "nimbus/base/atomic_file.hpp"
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
    // A probe named as write_atomically names its temporary (so a name too long for it fails
    // here), unique to this call: checks of one path at once, from threads or processes, and
    // leftover files never collide with it.
    fs::path probe;
    try {
      probe = create_file_beside(path);
    } catch (const std::system_error& e) {
      throw std::runtime_error(where + ": cannot be written (" + error_text(e.code().value()) + ")");
    }
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
  // A probe folder of a name no other check draws; should one exist, another is drawn.
  for (int attempt = 0;; ++attempt) {
    const fs::path probe = unique_name_beside(ancestor / "nimbus-probe", "");
    if (::mkdir(probe.c_str(), 0700) == 0) {
      ::rmdir(probe.c_str());
      return;
    }
    if (errno != EEXIST || attempt == 100)
      throw std::runtime_error(where + ": cannot create its directory in " + ancestor.string() + " (" + error_text(errno) + ")");
  }
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
