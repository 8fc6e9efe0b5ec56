// An error as one line, whatever it quotes: what the program prints on stderr and the Python
// module puts in its exceptions.
#pragma once
#include <cstddef>
#include <string>

namespace nimbus::cli {

// A line break becomes a space, any other control character (an escape sequence from a file's key
// or name) '?', and a message longer than kMaxErrorChars is cut in its middle, so that both what
// failed and why stay readable.
inline constexpr std::size_t kMaxErrorChars = 1000;
inline std::string one_line(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
    else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  if (text.size() > kMaxErrorChars)
    text = text.substr(0, kMaxErrorChars / 2) + " [...] " + text.substr(text.size() - kMaxErrorChars / 2);
  return text;
}

}  // namespace nimbus::cli
