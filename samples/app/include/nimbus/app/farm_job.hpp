// A farm job: a nimbus command cut into job-array tasks (frames in chunks, or bricks), the
// files each task must leave, and the scripts a scheduler runs. `nimbus farm slurm` writes and
// submits it; `nimbus farm check` reads it back and lists what is missing or unreadable.
#pragma once
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace nimbus::app {

struct FarmTask {
  std::vector<std::string> outputs;  // files the task writes, as the command names them
  std::string what;                  // "frames 1001-1004", "brick 3 of 2x2x1"
};

struct FarmJob {
  std::string kind;                  // "frames" or "bricks"
  std::string nimbus;                // absolute path of the nimbus program the tasks run
  std::string workdir;               // absolute; relative paths in the command are from here
  std::string dir;                   // absolute job directory: scripts, job.json, logs/, bricks/
  std::vector<std::string> command;  // the nimbus command and its arguments, as given
  int chunk = 1;                     // frames per task
  std::string bricks;                // layout text for --brick, bricks only ("4", "2x2x1")
  std::string merge_output;          // bricks only: the joined file (the command's -o)
  int first = 0, last = 0;           // frames only: the command's --frames
  std::string output, preview;       // frames only: the command's -o and --preview (sequence names)
  std::vector<FarmTask> tasks;       // made from the fields above (make_farm_tasks), not stored
  std::optional<std::filesystem::file_time_type> submitted;  // read back: job.json's time (outputs older are stale)
};

// The job's tasks from its fields; UsageError when they are inconsistent (a bad pattern, a
// range past the limits, more than 10^6 tasks, a brick layout outside 1 to 4096 bricks).
void make_farm_tasks(FarmJob& job);

// The job for `command` (generate or render with --frames A-B; or generate with `bricks` set).
// Throws UsageError naming what is wrong: another command, no -o, no --frames for frames,
// --frames with bricks, or flags the farm sets itself (--frame-from-env, --chunk, --brick).
FarmJob plan_farm_job(const std::vector<std::string>& command, int chunk, const std::string& bricks,
                      const std::filesystem::path& dir);

// job.json's text: the fields, not the tasks (a million frames stay a few hundred bytes).
// std::runtime_error when it would exceed the limit read_farm_job enforces (16 MiB).
std::string farm_job_json(const FarmJob& job);
// job.json of a job directory read back with every field checked and the tasks made again
// (std::runtime_error naming the file).
FarmJob read_farm_job(const std::filesystem::path& dir);

// The task's command line: the frames of task $SLURM_ARRAY_TASK_ID, or its brick, as arguments.
std::vector<std::string> task_arguments(const FarmJob& job);

// What is wrong with task `index`'s outputs: one line per missing, empty, stale (older than the
// job's job.json: left by an earlier run) or unreadable file (VDB: nimbus's seal and grids; EXR:
// the whole image; PNG: its signature). Empty when complete.
std::vector<std::string> check_task_outputs(const FarmJob& job, int index);

// A path of the job as the tasks see it: absolute ones as they are, others from job.workdir.
std::filesystem::path job_path(const FarmJob& job, const std::string& path);

}  // namespace nimbus::app
