// "--frames A-B" (or one frame number), --time, --fps and job-array tasks as the commands that
// write sequences read them: which frames this run writes, and each frame's time.
#pragma once
#include <cmath>
#include <cstdlib>
#include <algorithm>
#include <cstdio>
#include <optional>
#include <regex>
#include <string>
#include <tuple>
#include <utility>

#include "nimbus/app/usage_error.hpp"
#include "nimbus/base/validate.hpp"
#include "nimbus/volume/sky_ranges.hpp"

namespace nimbus::app {

// A sequence longer than this needs --many-frames: a typo such as 1-1000000 would otherwise start
// writing a million files.
inline constexpr long kMaxFramesUnforced = 10000;

// A time in seconds for a message: "t = 1e+12 s".
inline std::string time_text(double seconds) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "t = %g s", seconds);
  return buf;
}

// "[-1e+09, 1e+09] s of sky time (31 years either way)": the one range of sky times
// (volume::kSkyTimeRangeS), as every check of a time words it.
inline std::string sky_time_range_text() {
  return volume::range_text(volume::kSkyTimeRangeS) + " s of sky time (31 years either way)";
}

// UsageError "--time: t = 1e+12 s is outside [-1e+09, 1e+09] s of sky time ..." unless `seconds`
// lies in volume::kSkyTimeRangeS: the check of --time, and of the Python module's time
// (generate_plan.hpp), word for word.
inline void check_sky_time(double seconds) {
  if (!volume::kSkyTimeRangeS.holds(seconds))
    throw UsageError("--time: " + time_text(seconds) + " is outside " + sky_time_range_text());
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

// How a sequence-writing command (generate, render) is told its frames:
//   --time T                       one picture at T seconds, or
//   --frames A-B [--fps F]         frames A..B, frame n at sky time (n - S) x P, where S is
//   [--start-frame S]              --start-frame (default 0; 1001 is common in film work) and P
//   [--time-scale P]               the sky seconds per frame: realtime (1 / F, the default),
//                                  timelapse (kTimelapseSecondsPerFrame) or a number of seconds;
//   [--frame-from-env VAR]         only the frames of task $VAR of a job array (0-based), each
//   [--chunk K]                    task taking K consecutive frames (default 1).
// Frame n depends on (parameters, seed, n) alone, so any task order gives the same files.
struct FrameArgs {
  std::optional<double> time;
  std::string frames;
  double fps = 24.0;
  std::string time_scale;  // --time-scale: empty or "realtime", "timelapse", or seconds per frame
  bool many_frames = false;
  int start_frame = 0;
  std::string frame_from_env;  // name of the environment variable holding the task id
  int chunk = 1;
};

// The frames this run writes.
struct FrameRange {
  int first = 0, last = 0;  // this run's frames (a task's chunk, or all of --frames)
  int whole_first = 0, whole_last = 0;  // all of --frames
  bool sequence = false;    // --frames was given
  int start_frame = 0;
  double fps = 24.0;
  // Sky seconds between frames (--time-scale); 0: real time, 1 / fps (divided by fps, so that real
  // time gives the times it always gave, to the bit).
  double seconds_per_frame = 0.0;
  double single_time = 0.0;  // --time (no sequence)
  // Seconds of `frame`'s picture.
  double time(int frame) const {
    if (!sequence) return single_time;
    return seconds_per_frame > 0.0 ? double(frame - start_frame) * seconds_per_frame : double(frame - start_frame) / fps;
  }
};

// A named time-lapse: 10 sky seconds per frame. At 24 fps a second of film is 4 minutes of sky, so
// a 3-second shot shows 12 minutes: about one fair-weather cumulus's life (10-30 min; Stull 2017,
// ch. 6), its turrets rising and fading, as photographers' cloud time-lapses take a frame every
// 2-10 s.
inline constexpr double kTimelapseSecondsPerFrame = 10.0;

// --time-scale: sky seconds per frame, 0 for real time (1 / fps); UsageError naming the flag for
// anything but realtime, timelapse or a number in (0, 86400].
inline double parse_time_scale(const std::string& text) {
  if (text.empty() || text == "realtime") return 0.0;
  if (text == "timelapse") return kTimelapseSecondsPerFrame;
  const std::optional<double> v = parse_double(text);
  if (!v || !(*v > 0.0 && *v <= 86400.0))
    throw UsageError("--time-scale: '" + text.substr(0, 40) +
                     "' must be realtime, timelapse or sky seconds per frame in (0, 86400]");
  return *v;
}

// How many tasks of `chunk` frames cover first..last.
inline long task_count(int first, int last, int chunk) { return (long(last) - first + chunk) / chunk; }

// The task id in environment variable `var`: UsageError naming it when unset, empty or not a
// non-negative integer.
inline long task_id_from_env(const std::string& var) {
  const char* v = std::getenv(var.c_str());
  if (!v || !*v)
    throw UsageError("--frame-from-env: " + var + " is not set (run this inside a job array task, or drop the flag)");
  const std::string text(v);
  if (text.size() > 9 || !std::regex_match(text, std::regex(R"(\d+)")))
    throw UsageError("--frame-from-env: " + var + "='" + text.substr(0, 40) + "' is not a task id (an integer >= 0)");
  return std::stol(text);
}

// UsageError naming the flag for a time outside volume::kSkyTimeRangeS, a bad fps, a bad range, a time with a range,
// more than kMaxFramesUnforced frames without --many-frames, --frame-from-env or --chunk without
// --frames, a chunk below 1, or a task id beyond the range's tasks.
inline FrameRange parse_frames(const FrameArgs& a) {
  if (a.time) check_sky_time(*a.time);
  if (!(std::isfinite(a.fps) && a.fps > 0)) throw UsageError("--fps: must be finite and > 0");
  if (a.chunk < 1) throw UsageError("--chunk: must be at least 1 frame");
  if (std::abs(a.start_frame) > 9999999) throw UsageError("--start-frame: must be within +-9999999");
  FrameRange r;
  r.sequence = !a.frames.empty();
  r.fps = a.fps;
  r.start_frame = a.start_frame;
  r.single_time = a.time.value_or(0.0);
  r.seconds_per_frame = parse_time_scale(a.time_scale);
  if (!r.sequence) {
    if (!a.time_scale.empty()) throw UsageError("--time-scale: needs --frames A-B (it spaces a sequence's frames)");
    if (!a.frame_from_env.empty()) throw UsageError("--frame-from-env: needs --frames A-B (the whole sequence)");
    if (a.chunk != 1) throw UsageError("--chunk: needs --frames A-B and --frame-from-env");
    if (a.start_frame != 0) throw UsageError("--start-frame: needs --frames A-B");
    return r;
  }
  if (a.time) throw UsageError("--time and --frames: give one, not both");
  std::tie(r.first, r.last) = parse_frame_range(a.frames);
  r.whole_first = r.first;
  r.whole_last = r.last;
  // Every frame's time is checked now, not when its turn comes (--fps 1e-300 put frame 1 at
  // 1e300 s, after frame 0 was written): the first and last frames bound them all.
  for (const int f : {r.first, r.last})
    if (!volume::kSkyTimeRangeS.holds(r.time(f)))
      throw UsageError(std::string(a.time_scale.empty() ? "--fps" : "--time-scale") + ": frame " + std::to_string(f) +
                       " would be at " + time_text(r.time(f)) + ", outside " + sky_time_range_text() + "; " +
                       (a.time_scale.empty() ? "raise --fps" : "lower --time-scale") + " or move --start-frame");
  const long count = long(r.last) - r.first + 1;
  if (count > kMaxFramesUnforced && !a.many_frames)
    throw UsageError("--frames: " + a.frames + " is " + std::to_string(count) + " frames, more than " +
                     std::to_string(kMaxFramesUnforced) + "; add --many-frames to write that many");
  if (a.frame_from_env.empty()) {
    if (a.chunk != 1) throw UsageError("--chunk: needs --frame-from-env (a task of a job array)");
    return r;
  }
  const long tasks = task_count(r.first, r.last, a.chunk);
  const long task = task_id_from_env(a.frame_from_env);
  if (task >= tasks)
    throw UsageError("--frame-from-env: " + a.frame_from_env + "=" + std::to_string(task) + " is beyond the " +
                     std::to_string(tasks) + " tasks of --frames " + a.frames + " in chunks of " +
                     std::to_string(a.chunk) + " (task ids 0-" + std::to_string(tasks - 1) + ")");
  const long first = r.first + task * a.chunk;
  r.last = int(std::min<long>(r.last, first + a.chunk - 1));
  r.first = int(first);
  return r;
}

}  // namespace nimbus::app
