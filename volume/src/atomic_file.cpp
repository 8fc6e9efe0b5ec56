// Temporary-file-then-rename writes.
#include "nimbus/volume/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <stdexcept>
#include <string>

namespace nimbus::volume {

void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path&)>& write) {
  namespace fs = std::filesystem;
  if (path.empty()) throw std::invalid_argument("output path is empty");
  const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) throw std::runtime_error("cannot create directory " + parent.string() + ": " + ec.message());
  if (fs::is_directory(path)) throw std::runtime_error(path.string() + " is a directory");
  static std::atomic<unsigned> counter{0};
  const fs::path tmp = parent / ("." + path.filename().string() + ".tmp" +
                                 std::to_string(::getpid()) + "." + std::to_string(counter++));
  try {
    write(tmp);
    fs::rename(tmp, path);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
}

}  // namespace nimbus::volume
