// The frame flags of the commands that write sequences (generate, render): registered with CLI11
// here, read by the app library (nimbus/app/frame_range.hpp).
#pragma once
#include <string>

#include "cli.hpp"
#include "nimbus/app/frame_range.hpp"

namespace nimbus::cli {

using app::FrameArgs;
using app::FrameRange;
using app::kMaxFramesUnforced;
using app::parse_frames;
using app::task_count;
using app::time_text;

// Registers --time, --frames, --fps, --time-scale, --many-frames, --start-frame, --frame-from-env and --chunk.
inline void add_frame_options(CLI::App* cmd, FrameArgs& a, const std::string& what) {
  cmd->add_option("--time", a.time, "time in seconds (wind and evolution)");
  cmd->add_option("--frames", a.frames, "frames A-B, written as a sequence " + what +
                                            " (a %04d field, or the frame before the extension)");
  cmd->add_option("--fps", a.fps, "frames per second of the film (file metadata; with the default --time-scale, "
                                  "frame n is at sky time (n - start frame) / fps)")
      ->capture_default_str();
  cmd->add_option("--time-scale", a.time_scale,
                  "sky seconds per frame: realtime (1 / fps, the default), timelapse (10 s: a 3-second shot at 24 fps "
                  "shows 12 minutes of clouds boiling) or a number of seconds");
  cmd->add_flag("--many-frames", a.many_frames, "allow --frames to span more than 10000 frames");
  cmd->add_option("--start-frame", a.start_frame, "the frame at time 0 (1001 is common)")->capture_default_str();
  cmd->add_option("--frame-from-env", a.frame_from_env,
                  "only the frames of the job-array task whose 0-based id is in this environment variable "
                  "(e.g. SLURM_ARRAY_TASK_ID)");
  cmd->add_option("--chunk", a.chunk, "frames per task with --frame-from-env")->capture_default_str();
}

}  // namespace nimbus::cli
