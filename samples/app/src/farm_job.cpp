// Planning a farm job from a nimbus command, storing it, and checking its tasks' outputs.
#include "nimbus/app/farm_job.hpp"

#include <fstream>
#include <iterator>
#include <regex>

#include "nimbus/app/frame_range.hpp"
#include "nimbus/app/sequence_path.hpp"
#include "nimbus/app/usage_error.hpp"
#include "nimbus/base/input_limits.hpp"
#include "nimbus/render/image/image_io.hpp"
#include "nimbus/volume/json_io.hpp"
#include "nimbus/volume/vdb_read.hpp"

namespace nimbus::app {
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

// Whether `path` is `folder` or lies inside it, as the file system resolves both (links and
// other spellings included).
bool lies_within(const std::filesystem::path& path, const std::filesystem::path& folder) {
  std::error_code ec;
  std::filesystem::path p = std::filesystem::weakly_canonical(path, ec);
  if (ec) p = path.lexically_normal();
  std::filesystem::path f = std::filesystem::weakly_canonical(folder, ec);
  if (ec) f = folder.lexically_normal();
  auto pi = p.begin();
  for (auto fi = f.begin(); fi != f.end(); ++fi, ++pi) {
    if (fi->empty() && std::next(fi) == f.end()) break;  // a trailing separator
    if (pi == p.end() || *pi != *fi) return false;
  }
  return true;
}

int brick_count(const std::string& layout) {
  std::smatch m;
  if (std::regex_match(layout, m, std::regex(R"((\d{1,4})x(\d{1,4})x(\d{1,4}))")))
    return std::stoi(m[1]) * std::stoi(m[2]) * std::stoi(m[3]);
  if (std::regex_match(layout, std::regex(R"(\d{1,4})"))) return std::stoi(layout);
  return 0;
}

}  // namespace

std::filesystem::path job_path(const FarmJob& job, const std::string& path) {
  const std::filesystem::path p(path);
  return p.is_absolute() ? p : std::filesystem::path(job.workdir) / p;
}

constexpr long kMaxFarmFrames = 100000;  // 69 minutes at 24 fps; farm check lists every output

void make_farm_tasks(FarmJob& job) {
  job.tasks.clear();
  if (job.chunk < 1 || job.chunk > 1000000) throw UsageError("--chunk: must be in [1, 1000000] frames");
  if (job.kind == "bricks") {
    const int n = brick_count(job.bricks);
    if (n < 1 || n > 4096) throw UsageError("--bricks: '" + echo(job.bricks) + "' must be N or AxBxC, 1 to 4096 bricks in all");
    for (int i = 0; i < n; ++i)
      job.tasks.push_back({{(std::filesystem::path(job.dir) / "bricks" / ("brick." + frame_number_text(i, 4) + ".vdb")).string()},
                           "brick " + std::to_string(i) + " of " + job.bricks});
    return;
  }
  if (job.kind != "frames") throw UsageError("kind: '" + echo(job.kind) + "' must be frames or bricks");
  if (job.last < job.first || std::abs(job.first) > 9999999 || std::abs(job.last) > 9999999)
    throw UsageError("--frames: " + std::to_string(job.first) + "-" + std::to_string(job.last) + " is not a range within +-9999999");
  check_sequence_pattern("COMMAND -o", job.output);
  if (!job.preview.empty()) check_sequence_pattern("COMMAND --preview", job.preview);
  // Every frame's outputs are listed and looked up by the check: a farm job holds at most 10^5 frames.
  if (long(job.last) - job.first + 1 > kMaxFarmFrames)
    throw UsageError("--frames: " + std::to_string(job.first) + "-" + std::to_string(job.last) +
                     " is more than 100000 frames for one farm job; cut it into several jobs");
  const long tasks = task_count(job.first, job.last, job.chunk);
  for (long t = 0; t < tasks; ++t) {
    const int a = int(job.first + t * job.chunk), b = int(std::min<long>(job.last, job.first + (t + 1) * job.chunk - 1));
    FarmTask task;
    task.what = a == b ? "frame " + std::to_string(a) : "frames " + std::to_string(a) + "-" + std::to_string(b);
    for (int f = a; f <= b; ++f) {
      task.outputs.push_back(sequence_path(job.output, f, "COMMAND -o"));
      if (!job.preview.empty()) task.outputs.push_back(sequence_path(job.preview, f, "COMMAND --preview"));
    }
    job.tasks.push_back(std::move(task));
  }
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
    job.kind = "bricks";
    job.bricks = bricks;
    job.merge_output = output;
    // The joined file goes outside the job folder, which is the farm's own (job.json, the scripts,
    // logs/, bricks/ that merge reads): inside it, it could be one of them, or be replaced by the
    // next farm slurm --dir there.
    if (lies_within(job_path(job, output), job.dir))
      throw UsageError("COMMAND -o '" + echo(output, 200) + "': lies inside the job folder --dir '" + echo(job.dir, 200) +
                       "', which holds the farm's own files (job.json, scripts, logs/, bricks/); write the joined file "
                       "outside it");
    make_farm_tasks(job);
    return job;
  }
  const auto [frames, frames_at] = option_value(command, {"--frames"});
  if (frames.empty()) throw UsageError("COMMAND: needs --frames A-B (or give --bricks for a brick job)");
  std::tie(job.first, job.last) = parse_frame_range(frames);
  job.output = output;
  job.preview = option_value(command, {"--preview"}).first;
  job.kind = "frames";
  make_farm_tasks(job);
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

std::string farm_job_json(const FarmJob& job) {
  nlohmann::json j;
  j["nimbus"] = "farm job";
  j["kind"] = job.kind;
  j["program"] = job.nimbus;
  j["workdir"] = job.workdir;
  j["dir"] = job.dir;
  j["command"] = job.command;
  j["chunk"] = job.chunk;
  if (job.kind == "bricks") {
    j["bricks"] = job.bricks;
    j["merge_output"] = job.merge_output;
  } else {
    j["frames"] = {job.first, job.last};
    j["output"] = job.output;
    j["preview"] = job.preview;
  }
  // replace: a command's argument that is not UTF-8 is kept readable instead of failing the dump.
  std::string text = j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
  if (text.size() > kMaxInputFileBytes)
    throw UsageError("COMMAND: the job's description would take " + std::to_string(text.size() >> 20) +
                     " MiB, more than the 16 MiB nimbus farm check reads");
  return text;
}

FarmJob read_farm_job(const std::filesystem::path& dir) {
  const std::string path = (dir / "job.json").string();
  const nlohmann::json j = volume::read_json_file(path, "farm job");
  const std::string where = "farm job '" + echo(path, 200) + "'";
  FarmJob job;
  try {
    if (!j.is_object() || j.value("nimbus", "") != "farm job")
      throw std::invalid_argument("not a job.json of nimbus farm slurm (no \"nimbus\": \"farm job\")");
    job.kind = j.at("kind").get<std::string>();
    job.nimbus = j.at("program").get<std::string>();
    job.workdir = j.at("workdir").get<std::string>();
    job.dir = j.at("dir").get<std::string>();
    job.command = j.at("command").get<std::vector<std::string>>();
    job.chunk = volume::json_integer(j.at("chunk"), "chunk", 1, 1000000);
    if (job.kind == "bricks") {
      job.bricks = j.at("bricks").get<std::string>();
      job.merge_output = j.at("merge_output").get<std::string>();
    } else {
      const nlohmann::json& f = j.at("frames");
      if (!f.is_array() || f.size() != 2) throw std::invalid_argument("frames must be [first, last]");
      job.first = volume::json_integer(f[0], "frames[0]", -9999999, 9999999);
      job.last = volume::json_integer(f[1], "frames[1]", -9999999, 9999999);
      job.output = j.at("output").get<std::string>();
      job.preview = j.at("preview").get<std::string>();
    }
    make_farm_tasks(job);
    std::error_code ec;
    const auto written = std::filesystem::last_write_time(path, ec);
    if (!ec) job.submitted = written;
  } catch (const std::exception& e) {  // nlohmann's out_of_range / type_error, or a field's check
    throw std::runtime_error(where + ": " + echo(e.what(), 300));
  }
  return job;
}

std::vector<std::string> check_task_outputs(const FarmJob& job, int index) {
  std::vector<std::string> problems;
  // job.json is written when the job is submitted: an output older than it is from an earlier run.
  const std::optional<std::filesystem::file_time_type>& submitted = job.submitted;
  for (const std::string& out : job.tasks.at(std::size_t(index)).outputs) {
    const std::filesystem::path p = job_path(job, out);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(p, ec)) {
      problems.push_back("missing " + echo(out, 300));
      continue;
    }
    if (std::filesystem::file_size(p, ec) == 0) {
      problems.push_back("empty " + echo(out, 300));
      continue;
    }
    if (submitted && std::filesystem::last_write_time(p, ec) < *submitted) {
      problems.push_back("stale " + echo(out, 300) + " (written before this job)");
      continue;
    }
    const std::string ext = p.extension().string();
    try {
      if (ext == ".vdb") {
        const volume::VolumeFile f = volume::read_volume_vdb(p, volume::VdbReadOptions{});
        if (!f.checksum_verified) problems.push_back("not sealed by nimbus " + echo(out, 300));
      } else if (ext == ".exr") {
        render::read_exr(p);
      } else if (ext == ".png") {
        std::ifstream in(p, std::ios::binary);
        char sig[8] = {};
        in.read(sig, 8);
        if (std::string(sig, 8) != "\x89PNG\r\n\x1a\n") problems.push_back("not a PNG " + echo(out, 300));
      }
    } catch (const std::exception& e) {
      problems.push_back("unreadable " + echo(out, 300) + " (" + echo(e.what(), 200) + ")");
    }
  }
  return problems;
}

}  // namespace nimbus::app
