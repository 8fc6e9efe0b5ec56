// Names of the files of a sequence, the same for every command that writes or reads one
// (generate, render): "name.%04d.vdb" holds a frame field (nimbus/base/sequence_pattern.hpp); a
// name without one gets the frame inserted before its extension, "name.exr" -> "name.0007.exr".
#pragma once
#include <string>

#include "nimbus/app/usage_error.hpp"
#include "nimbus/base/sequence_pattern.hpp"

namespace nimbus::app {

// UsageError naming `flag` unless `pattern` holds no '%' or exactly one frame field %d / %0Nd
// (N from 1 to 9).
inline SequencePattern check_sequence_pattern(const std::string& flag, const std::string& pattern) {
  try {
    return SequencePattern::parse(pattern, flag);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

inline bool has_frame_field(const std::string& pattern) { return pattern.find('%') != std::string::npos; }

// The file of `frame`: the frame field filled in, or ".%04d" inserted before the extension (after
// the last '/'; appended when there is none). UsageError naming `flag` for a bad pattern.
inline std::string sequence_path(const std::string& pattern, int frame, const std::string& flag = "-o") {
  const SequencePattern p = check_sequence_pattern(flag, pattern);
  if (p.has_field) return p.path(frame);
  const std::size_t dot = pattern.rfind('.');
  const std::size_t slash = pattern.rfind('/');
  const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash) && dot > 0 &&
                       (slash == std::string::npos || dot > slash + 1);
  const std::string number = "." + frame_number_text(frame, 4);
  return has_ext ? pattern.substr(0, dot) + number + pattern.substr(dot) : pattern + number;
}

}  // namespace nimbus::app
