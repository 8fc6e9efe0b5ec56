// An OpenEXR input stream over a regular file's descriptor (exr_input_stream.hpp).
#include "exr_input_stream.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "nimbus/base/file_kind.hpp"

namespace nimbus::render {

ExrInputStream::ExrInputStream(const std::string& path) : Imf::IStream(path.c_str()) {
  // O_NONBLOCK: should a FIFO have taken the file's place since read_exr checked the name,
  // open() still returns, and fstat says what it is.
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd_ < 0) throw std::runtime_error(std::string("cannot be opened (") + std::strerror(errno) + ")");
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    const std::string kind = file_kind(st.st_mode);
    ::close(fd_);
    throw std::runtime_error(std::string("is not a regular file (it is ") + kind + " now)");
  }
  size_ = static_cast<std::uint64_t>(st.st_size);
}

ExrInputStream::~ExrInputStream() { ::close(fd_); }

std::size_t ExrInputStream::read_at(std::uint64_t pos, char* out, std::size_t n) const {
  std::size_t done = 0;
  while (done < n) {
    const ssize_t got = ::pread(fd_, out + done, n - done, static_cast<off_t>(pos + done));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw std::runtime_error(std::string("read error (") + std::strerror(errno) + ")");
    if (got == 0) break;  // the end of the file
    done += static_cast<std::size_t>(got);
  }
  return done;
}

bool ExrInputStream::read(char c[], int n) {
  if (n < 0) throw std::runtime_error("negative read size");
  const std::size_t got = read_at(pos_, c, static_cast<std::size_t>(n));
  pos_ += got;
  if (got < static_cast<std::size_t>(n)) throw std::runtime_error("unexpected end of file");
  return pos_ < size_;
}

}  // namespace nimbus::render
