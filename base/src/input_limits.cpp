// Bounded reading of input files and lines (input_limits.hpp).
#include "nimbus/base/input_limits.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "nimbus/base/file_kind.hpp"

namespace nimbus {
namespace {

std::string mib(std::uintmax_t bytes) { return std::to_string(bytes >> 20) + " MiB"; }

}  // namespace

std::string read_regular_file(const std::string& path, const std::string& where, std::uintmax_t max_bytes) {
  struct stat st {};
  if (path.empty()) throw std::runtime_error(where + ": the file name is empty");
  if (::stat(path.c_str(), &st) != 0) throw std::runtime_error(where + ": cannot be read (" + std::strerror(errno) + ")");
  if (!S_ISREG(st.st_mode)) throw std::runtime_error(where + ": is " + file_kind(st.st_mode) + ", not a regular file");
  if (static_cast<std::uintmax_t>(st.st_size) > max_bytes)
    throw std::runtime_error(where + ": larger than the limit of " + mib(max_bytes));
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw std::runtime_error(where + ": cannot be read (" + std::strerror(errno) + ")");
  std::string text;
  std::string error;
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) error = ": is no longer a regular file";
  char buf[65536];
  while (error.empty()) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) error = std::string(": cannot be read (") + std::strerror(errno) + ")";
    if (n <= 0) break;
    text.append(buf, static_cast<std::size_t>(n));
    if (text.size() > max_bytes) error = ": larger than the limit of " + mib(max_bytes);
  }
  ::close(fd);
  if (!error.empty()) throw std::runtime_error(where + error);
  return text;
}

void refuse_special_file(const std::string& path, const std::string& what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    throw std::runtime_error(what + " '" + path + "': is " + file_kind(st.st_mode) + ", not a regular file");
}

void check_json_depth(std::string_view text, const std::string& what, int max_depth) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;  // the escaped character cannot end the string
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth)
        throw std::runtime_error(what + ": JSON nested deeper than " + std::to_string(max_depth) + " levels");
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
}

LineRead read_line_limited(std::istream& in, std::string& line, std::size_t max_bytes) {
  line.clear();
  std::streambuf* sb = in.rdbuf();
  for (;;) {
    const int c = sb->sbumpc();
    if (c == std::char_traits<char>::eof()) {
      in.setstate(std::ios::eofbit);
      return line.empty() ? LineRead::End : LineRead::Line;
    }
    if (c == '\n') break;
    if (line.size() == max_bytes) return LineRead::TooLong;
    line.push_back(static_cast<char>(c));
  }
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return LineRead::Line;
}

std::string echo(std::string_view text, std::size_t max_chars) {
  std::string out(text.substr(0, max_chars));
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  if (text.size() > max_chars) out += "...";
  return out;
}

}  // namespace nimbus
