// "--frames A-B" (or one frame number) as the commands that write sequences read it.
#pragma once
#include <cmath>
#include <cstdio>
#include <optional>
#include <regex>
#include <string>
#include <tuple>
#include <utility>

#include "cli.hpp"

namespace nimbus::cli {

// A sequence longer than this needs --many-frames: a typo such as 1-1000000 would otherwise start
// writing a million files.
inline constexpr long kMaxFramesUnforced = 10000;

// A time in seconds for a message: "t = 1e+12 s".
inline std::string time_text(double seconds) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "t = %g s", seconds);
  return buf;
}

// First and last frame; UsageError naming --frames when malformed or reversed.
inline std::pair<int, int> parse_frame_range(const std::string& text) {
  std::smatch m;
  if (!std::regex_match(text, m, std::regex(R"((-?\d{1,7})(?:-(-?\d{1,7}))?)")))
    throw UsageError("--frames: '" + text + "' must be A-B (e.g. 1-240) or one frame number");
  const int first = std::stoi(m[1]);
  const int last = m[2].matched ? std::stoi(m[2]) : first;
  if (last < first) throw UsageError("--frames: the last frame comes before the first");
  return {first, last};
}

// --time T | --frames A-B [--fps F] as the sequence-writing commands take them: UsageError
// naming the flag for a non-finite time, a bad fps, a bad range, a time with a range, or more
// than kMaxFramesUnforced frames without `many_frames` (--many-frames).
struct FrameRange {
  int first = 0, last = 0;
  bool sequence = false;  // --frames was given
};
inline FrameRange parse_frames(const std::optional<double>& time, const std::string& frames, double fps,
                               bool many_frames) {
  if (time && !std::isfinite(*time)) throw UsageError("--time: must be finite (seconds)");
  if (!(std::isfinite(fps) && fps > 0)) throw UsageError("--fps: must be finite and > 0");
  FrameRange r;
  r.sequence = !frames.empty();
  if (r.sequence) {
    if (time) throw UsageError("--time and --frames: give one, not both");
    std::tie(r.first, r.last) = parse_frame_range(frames);
    const long count = long(r.last) - r.first + 1;
    if (count > kMaxFramesUnforced && !many_frames)
      throw UsageError("--frames: " + frames + " is " + std::to_string(count) + " frames, more than " +
                       std::to_string(kMaxFramesUnforced) + "; add --many-frames to write that many");
  }
  return r;
}

}  // namespace nimbus::cli
