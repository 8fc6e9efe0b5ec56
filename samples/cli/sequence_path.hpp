// Names of the files of a sequence, the same for every command that writes or reads one
// (generate, render): "name.%04d.vdb" holds a printf frame field; a name without one gets the
// frame inserted before its extension, "name.exr" -> "name.0007.exr".
#pragma once
#include <algorithm>
#include <cstdio>
#include <regex>
#include <string>

#include "cli.hpp"

namespace nimbus::cli {

// UsageError naming `flag` unless `pattern` holds no '%' or exactly one frame field %d / %0Nd.
inline void check_sequence_pattern(const std::string& flag, const std::string& pattern) {
  const auto n = std::count(pattern.begin(), pattern.end(), '%');
  if (n == 0) return;
  if (n != 1 || !std::regex_search(pattern, std::regex(R"(%0?\d{0,2}d)")))
    throw UsageError(flag + ": '" + pattern + "' may hold one frame-number field such as %04d, and no other %");
}

inline bool has_frame_field(const std::string& pattern) { return pattern.find('%') != std::string::npos; }

// The file of `frame`: the frame field filled in, or ".%04d" inserted before the extension (after
// the last '/'; appended when there is none). Expects a pattern check_sequence_pattern accepts.
inline std::string sequence_path(const std::string& pattern, int frame) {
  char buf[64];
  const std::size_t field = pattern.find('%');
  if (field != std::string::npos) {
    const std::size_t end = pattern.find('d', field);
    std::snprintf(buf, sizeof buf, pattern.substr(field, end - field + 1).c_str(), frame);
    return pattern.substr(0, field) + buf + pattern.substr(end + 1);
  }
  const std::size_t dot = pattern.rfind('.');
  const std::size_t slash = pattern.rfind('/');
  const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash) && dot > 0 &&
                       (slash == std::string::npos || dot > slash + 1);
  std::snprintf(buf, sizeof buf, ".%04d", frame);
  return has_ext ? pattern.substr(0, dot) + buf + pattern.substr(dot) : pattern + buf;
}

}  // namespace nimbus::cli
