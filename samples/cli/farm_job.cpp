// Planning a farm job from a nimbus command, storing it, and checking its tasks' outputs.
#include "farm_job.hpp"

#include <fstream>
#include <regex>

#include "cli.hpp"
#include "frame_range.hpp"
#include "sequence_path.hpp"
#include "nimbus/base/input_limits.hpp"
#include "nimbus/render/image/image_io.hpp"
#include "nimbus/volume/json_io.hpp"
#include "nimbus/volume/vdb_read.hpp"

namespace nimbus::cli {
namespace {

// The value of the first of `names` in `args` ("-o X", "--output X" or "--output=X"), and its
// position (of the flag); npos when absent.
std::pair<std::string, std::size_t> option_value(const std::vector<std::string>& args,
                                                 std::initializer_list<const char*> names) {
  for (std::size_t i = 1; i < args.size(); ++i)
    for (const char* name : names) {
      const std::string n(name);
      if (args[i] == n) {
        if (i + 1 >= args.size()) throw UsageError("COMMAND: " + n + " has no value");
        return {args[i + 1], i};
      }
      if (n.size() > 2 && args[i].rfind(n + "=", 0) == 0) return {args[i].substr(n.size() + 1), i};
    }
  return {"", std::string::npos};
}

bool has_option(const std::vector<std::string>& args, const char* name) {
  return option_value(args, {name}).second != std::string::npos;
}

// The arguments without the option at `at` (and its value when separate).
std::vector<std::string> without_option(std::vector<std::string> args, std::size_t at) {
  const bool joined = args[at].find('=') != std::string::npos;
  args.erase(args.begin() + long(at), args.begin() + long(at) + (joined ? 1 : 2));
  return args;
}

int brick_count(const std::string& layout) {
  std::smatch m;
  if (std::regex_match(layout, m, std::regex(R"((\d{1,4})x(\d{1,4})x(\d{1,4}))")))
    return std::stoi(m[1]) * std::stoi(m[2]) * std::stoi(m[3]);
  if (std::regex_match(layout, std::regex(R"(\d{1,4})"))) return std::stoi(layout);
  return 0;
}

std::string four_digits(int i) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%04d", i);
  return buf;
}

}  // namespace

std::string shell_quote(const std::string& text) {
  std::string q = "'";
  for (char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::filesystem::path job_path(const FarmJob& job, const std::string& path) {
  const std::filesystem::path p(path);
  return p.is_absolute() ? p : std::filesystem::path(job.workdir) / p;
}

FarmJob plan_farm_job(const std::vector<std::string>& command, int chunk, const std::string& bricks,
                      const std::filesystem::path& dir) {
  if (command.empty()) throw UsageError("COMMAND: give the nimbus command after --, e.g. -- generate --preset ... --frames 1-240 -o out.%04d.vdb");
  const std::string& name = command[0];
  if (name != "generate" && name != "render")
    throw UsageError("COMMAND: '" + echo(name) + "' is not a command the farm cuts into tasks (generate or render)");
  for (const char* own : {"--frame-from-env", "--chunk", "--brick"})
    if (has_option(command, own)) throw UsageError(std::string("COMMAND: ") + own + " is set by the farm for each task; leave it out");
  const auto [output, output_at] = option_value(command, {"-o", "--output"});
  if (output.empty()) throw UsageError("COMMAND: needs -o (the file or sequence the tasks write)");
  check_sequence_pattern("COMMAND -o", output);

  FarmJob job;
  job.nimbus = std::filesystem::read_symlink("/proc/self/exe").string();
  job.workdir = std::filesystem::current_path().string();
  job.dir = std::filesystem::absolute(dir).lexically_normal().string();
  job.command = command;
  if (chunk < 1) throw UsageError("--chunk: must be at least 1 frame");
  job.chunk = chunk;
  if (!bricks.empty()) {
    if (name != "generate") throw UsageError("--bricks: only generate writes bricks");
    if (has_option(command, "--frames")) throw UsageError("--bricks: a brick job is of one time (--time), not --frames");
    if (chunk != 1) throw UsageError("--chunk: frames only; a brick job has one task per brick");
    if (has_frame_field(output)) throw UsageError("COMMAND -o: the joined file of a brick job has no frame field");
    const int n = brick_count(bricks);
    if (n < 1 || n > 4096) throw UsageError("--bricks: '" + echo(bricks) + "' must be N or AxBxC, 1 to 4096 bricks in all");
    job.kind = "bricks";
    job.bricks = bricks;
    job.merge_output = output;
    for (int i = 0; i < n; ++i)
      job.tasks.push_back({{(std::filesystem::path(job.dir) / "bricks" / ("brick." + four_digits(i) + ".vdb")).string()},
                           "brick " + std::to_string(i) + " of " + bricks});
    return job;
  }
  const auto [frames, frames_at] = option_value(command, {"--frames"});
  if (frames.empty()) throw UsageError("COMMAND: needs --frames A-B (or give --bricks for a brick job)");
  const auto [first, last] = parse_frame_range(frames);
  const auto [preview, preview_at] = option_value(command, {"--preview"});
  if (!preview.empty()) check_sequence_pattern("COMMAND --preview", preview);
  const long tasks = task_count(first, last, chunk);
  if (tasks > 1000000) throw UsageError("--frames: more than 10^6 tasks");
  job.kind = "frames";
  for (long t = 0; t < tasks; ++t) {
    const int a = int(first + t * chunk), b = int(std::min<long>(last, first + (t + 1) * chunk - 1));
    FarmTask task;
    task.what = a == b ? "frame " + std::to_string(a) : "frames " + std::to_string(a) + "-" + std::to_string(b);
    for (int f = a; f <= b; ++f) {
      task.outputs.push_back(sequence_path(output, f));
      if (!preview.empty()) task.outputs.push_back(sequence_path(preview, f));
    }
    job.tasks.push_back(task);
  }
  return job;
}

std::vector<std::string> task_arguments(const FarmJob& job) {
  if (job.kind == "bricks") {  // -o becomes the task's brick (the script adds it with --brick)
    return without_option(job.command, option_value(job.command, {"-o", "--output"}).second);
  }
  std::vector<std::string> args = job.command;
  args.insert(args.end(), {"--frame-from-env", "SLURM_ARRAY_TASK_ID", "--chunk", std::to_string(job.chunk)});
  return args;
}

void write_farm_job(const FarmJob& job) {
  nlohmann::json j;
  j["kind"] = job.kind;
  j["nimbus"] = job.nimbus;
  j["workdir"] = job.workdir;
  j["dir"] = job.dir;
  j["command"] = job.command;
  j["chunk"] = job.chunk;
  j["bricks"] = job.bricks;
  j["merge_output"] = job.merge_output;
  for (const FarmTask& t : job.tasks) j["tasks"].push_back({{"what", t.what}, {"outputs", t.outputs}});
  volume::write_json_file((std::filesystem::path(job.dir) / "job.json").string(), j, "farm job");
}

FarmJob read_farm_job(const std::filesystem::path& dir) {
  const std::string path = (dir / "job.json").string();
  const nlohmann::json j = volume::read_json_file(path, "farm job");
  FarmJob job;
  try {
    job.kind = j.at("kind").get<std::string>();
    if (job.kind != "frames" && job.kind != "bricks") throw std::invalid_argument("kind must be frames or bricks");
    job.nimbus = j.at("nimbus").get<std::string>();
    job.workdir = j.at("workdir").get<std::string>();
    job.dir = j.at("dir").get<std::string>();
    job.command = j.at("command").get<std::vector<std::string>>();
    job.chunk = j.at("chunk").get<int>();
    job.bricks = j.at("bricks").get<std::string>();
    job.merge_output = j.at("merge_output").get<std::string>();
    for (const auto& t : j.at("tasks")) job.tasks.push_back({t.at("outputs").get<std::vector<std::string>>(), t.at("what").get<std::string>()});
  } catch (const std::exception& e) {
    throw std::runtime_error("farm job '" + path + "': " + e.what());
  }
  if (job.tasks.empty()) throw std::runtime_error("farm job '" + path + "': no tasks");
  return job;
}

std::vector<std::string> check_task_outputs(const FarmJob& job, int index) {
  std::vector<std::string> problems;
  // job.json is written when the job is submitted: an output older than it is from an earlier run.
  std::error_code job_ec;
  const auto submitted = std::filesystem::last_write_time(std::filesystem::path(job.dir) / "job.json", job_ec);
  for (const std::string& out : job.tasks.at(std::size_t(index)).outputs) {
    const std::filesystem::path p = job_path(job, out);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(p, ec)) {
      problems.push_back("missing " + out);
      continue;
    }
    if (std::filesystem::file_size(p, ec) == 0) {
      problems.push_back("empty " + out);
      continue;
    }
    if (!job_ec && std::filesystem::last_write_time(p, ec) < submitted) {
      problems.push_back("stale " + out + " (written before this job)");
      continue;
    }
    const std::string ext = p.extension().string();
    try {
      if (ext == ".vdb") {
        const volume::VolumeFile f = volume::read_volume_vdb(p, volume::VdbReadOptions{});
        if (!f.checksum_verified) problems.push_back("not sealed by nimbus " + out);
      } else if (ext == ".exr") {
        render::read_exr(p);
      } else if (ext == ".png") {
        std::ifstream in(p, std::ios::binary);
        char sig[8] = {};
        in.read(sig, 8);
        if (std::string(sig, 8) != "\x89PNG\r\n\x1a\n") problems.push_back("not a PNG " + out);
      }
    } catch (const std::exception& e) {
      problems.push_back("unreadable " + out + " (" + echo(e.what(), 200) + ")");
    }
  }
  return problems;
}

}  // namespace nimbus::cli
