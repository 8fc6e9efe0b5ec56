// `nimbus farm slurm ... -- COMMAND`: a generate or render command cut into a Slurm job array
// (frames in chunks, or bricks), a dependent check job, and for bricks a merge job after it;
// `nimbus farm check DIR`: which tasks left missing or unreadable outputs (docs/farm.md).
#include <sys/stat.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "cli.hpp"
#include "nimbus/app/farm_job.hpp"
#include "nimbus/app/shell.hpp"
#include "nimbus/base/file_kind.hpp"
#include "nimbus/base/input_limits.hpp"
#include "nimbus/base/output_path.hpp"
#include "nimbus/base/staged_files.hpp"

namespace nimbus::cli {

using app::FarmJob;
using app::FarmTask;
using app::check_task_outputs;
using app::farm_job_json;
using app::job_path;
using app::make_farm_tasks;
using app::plan_farm_job;
using app::read_farm_job;
using app::shell_quote;
using app::task_arguments;
namespace {

struct SlurmArgs {
  std::string dir;
  int concurrency = 0;  // %N: tasks at once; 0 = no limit
  int chunk = 1;
  std::string bricks;
  std::string partition, mem, time_limit;
  int cpus_per_task = 2;
  int retries = 1;
  bool dry_run = false, wait = false, hold = false;
  std::vector<std::string> command;
};

struct CheckArgs {
  std::string dir;
  std::string array_job;  // the array's job id, for the log names
};

// At most the last `max_bytes` of a file, without its trailing empty lines, and from the start of
// the last line that begins within them: the end of a log, however large the log is.
std::string log_tail(const std::filesystem::path& path, std::uintmax_t max_bytes) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return "";
  if (!S_ISREG(st.st_mode)) return std::string("(the log is ") + file_kind(st.st_mode) + ", not read)";  // a FIFO would block
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size <= 0) return "";
  const std::streamoff from = size > std::streamoff(max_bytes) ? size - std::streamoff(max_bytes) : 0;
  in.seekg(from);
  std::string text(static_cast<std::size_t>(size - from), '\0');
  in.read(text.data(), std::streamsize(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text.substr(text.find_last_of('\n') == std::string::npos ? 0 : text.find_last_of('\n') + 1);
}

// The job folder's files, written all or nothing: each is refused up front when something other
// than a regular file stands in its place (a FIFO, a symbolic link, a device), the folders
// logs/ and bricks/ must be folders, and only when every file is complete are they renamed into
// place; on any failure nothing of the new job remains (folders made for it are removed).
void write_job_folder(const FarmJob& job, const std::vector<std::pair<std::string, std::string>>& files) {
  namespace fs = std::filesystem;
  const fs::path dir(job.dir);
  std::vector<fs::path> folders{dir, dir / "logs"};
  if (job.kind == "bricks") folders.push_back(dir / "bricks");
  for (const fs::path& f : folders) {
    std::error_code ec;
    const fs::file_status st = fs::symlink_status(f, ec);
    const bool is_dir_link = fs::is_symlink(st) && f == dir && fs::is_directory(fs::status(f, ec));
    if (fs::exists(st) && !fs::is_directory(st) && !is_dir_link)
      throw UsageError("--dir: '" + echo(f.string(), 200) + "' exists and is not a folder; choose another --dir");
  }
  // What stands in each file's place first (no probe file touches the folder before a refusal),
  // then whether the folder takes files.
  for (const auto& [name, text] : files) {
    struct stat st {};
    if (::lstat((dir / name).c_str(), &st) == 0 && !S_ISREG(st.st_mode))
      throw std::runtime_error("--dir '" + echo((dir / name).string(), 300) + "': is " + file_kind(st.st_mode) +
                               "; only a regular file is replaced");
  }
  for (const auto& [name, text] : files) check_output_path(dir / name, "--dir");
  std::vector<fs::path> made;  // folders this job created, removed again on failure
  try {
    for (const fs::path& f : folders) {
      std::error_code ec;
      if (!fs::exists(fs::symlink_status(f, ec))) {
        fs::create_directories(f);
        made.push_back(f);
      }
    }
    StagedFiles staged;
    for (const auto& [name, text] : files) {
      staged.write(dir / name, [&, &text = text](const fs::path& tmp) {
        std::ofstream out(tmp, std::ios::binary);
        out << text;
        out.close();
        if (!out) throw std::runtime_error("cannot write '" + tmp.string() + "'");
        if (name != "job.json")
          fs::permissions(tmp, fs::perms::owner_exec | fs::perms::group_exec, fs::perm_options::add);
      });
    }
    staged.commit();
  } catch (...) {
    for (auto it = made.rbegin(); it != made.rend(); ++it) {
      std::error_code ec;
      fs::remove_all(*it, ec);
    }
    throw;
  }
}

std::string sbatch_header(const SlurmArgs& a, const FarmJob& job, const std::string& name, const std::string& log) {
  std::string s = "#!/bin/bash\n# Written by nimbus farm slurm (docs/farm.md).\n";
  s += "#SBATCH --job-name=" + name + "\n";
  s += "#SBATCH --output=" + job.dir + "/logs/" + log + "\n";
  s += "#SBATCH --chdir=" + job.workdir + "\n";
  if (!a.partition.empty()) s += "#SBATCH --partition=" + a.partition + "\n";
  return s;
}

std::string join_quoted(const std::vector<std::string>& args) {
  std::string s;
  for (const std::string& x : args) s += (s.empty() ? "" : " ") + shell_quote(x);
  return s;
}

// The array script: each task runs its share, retried up to --retries times (not after a usage
// error, exit 2, which a retry cannot mend).
std::string task_script(const SlurmArgs& a, const FarmJob& job) {
  std::string s = sbatch_header(a, job, "nimbus-" + job.command[0], "task_%A_%a.log");
  s += "#SBATCH --array=0-" + std::to_string(job.tasks.size() - 1) +
       (a.concurrency > 0 ? "%" + std::to_string(a.concurrency) : "") + "\n";
  s += "#SBATCH --cpus-per-task=" + std::to_string(a.cpus_per_task) + "\n";
  if (!a.mem.empty()) s += "#SBATCH --mem=" + a.mem + "\n";
  if (!a.time_limit.empty()) s += "#SBATCH --time=" + a.time_limit + "\n";
  s += "set -u\n";
  s += "i=${SLURM_ARRAY_TASK_ID:?not a job-array task}\n";
  s += "retries=" + std::to_string(a.retries) + "\n";
  s += "attempt=0\n";
  s += "while :; do\n";
  s += "  echo \"nimbus farm: task $i, attempt $((attempt + 1)), on $(hostname)\"\n";
  std::string run = "  " + shell_quote(job.nimbus) + " " + join_quoted(task_arguments(job));
  if (job.kind == "bricks")
    run += " --brick \"$i/" + job.bricks + "\" -o \"$(printf " + shell_quote(job.dir + "/bricks/brick.%04d.vdb") + " \"$i\")\"";
  s += run + "\n";
  s += "  rc=$?\n";
  s += "  [ $rc -eq 0 ] && exit 0\n";
  s += "  echo \"nimbus farm: task $i failed with exit $rc\" >&2\n";
  s += "  [ $rc -eq 2 ] && exit 2\n";
  s += "  attempt=$((attempt + 1))\n";
  s += "  [ $attempt -gt $retries ] && exit $rc\n";
  s += "done\n";
  return s;
}

std::string check_script(const SlurmArgs& a, const FarmJob& job) {
  return sbatch_header(a, job, "nimbus-check", "check_%j.log") + "#SBATCH --cpus-per-task=1\n" +
         shell_quote(job.nimbus) + " farm check " + shell_quote(job.dir) + " --array-job \"$1\"\n";
}

std::string merge_script(const SlurmArgs& a, const FarmJob& job) {
  std::vector<std::string> args{job.nimbus, "merge"};
  for (const FarmTask& t : job.tasks) args.push_back(t.outputs[0]);
  args.insert(args.end(), {"-o", job.merge_output});
  std::string s = sbatch_header(a, job, "nimbus-merge", "merge_%j.log") + "#SBATCH --cpus-per-task=1\n";
  if (!a.mem.empty()) s += "#SBATCH --mem=" + a.mem + "\n";
  return s + join_quoted(args) + "\n";
}

// A command line's exit status (128 + the signal that ended it) and output (nimbus/app/shell.hpp).
std::pair<int, std::string> run_line(const std::string& line) {
  const app::ShellResult r = app::run_shell(line);
  return {r.signal ? 128 + r.signal : r.exit_code, r.output};
}

std::string job_id(const std::string& sbatch_output, const std::string& what) {
  std::string id = sbatch_output.substr(0, sbatch_output.find_first_of(";\n"));
  if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
    throw std::runtime_error("sbatch did not submit the " + what + ": " + echo(sbatch_output, 400));
  return id;
}

// The last non-empty line of a log, read from its last 64 KiB only: a task's log may be huge
// (or a sparse file of terabytes) and is not read whole.
std::string last_line(const std::filesystem::path& path) {
  return echo(log_tail(path, 64 * 1024), 300);
}

// Runs `nimbus --check-only` on task `index`'s command line, as its job-array task would run it
// (the same program, working directory and arguments, the task id in SLURM_ARRAY_TASK_ID). A
// refusal is rethrown with the task's own message: UsageError for its exit 2, else runtime_error.
void check_task_command(const FarmJob& job, std::size_t index) {
  std::vector<std::string> args = task_arguments(job);
  if (job.kind == "bricks")
    args.insert(args.end(), {"--brick", std::to_string(index) + "/" + job.bricks, "-o", job.tasks[index].outputs[0]});
  std::string line = "SLURM_ARRAY_TASK_ID=" + std::to_string(index) + " " + shell_quote(job.nimbus) + " --check-only";
  for (const std::string& arg : args) line += " " + shell_quote(arg);
  // Its stderr alone (the one line a refusal prints); its stdout is dropped.
  const auto [rc, said] = run_line("{ " + line + " 2>&1 >/dev/null </dev/null; }");
  if (rc == 0) return;
  std::string first = said.substr(0, said.find('\n'));
  if (first.rfind("nimbus: ", 0) == 0) first = first.substr(8);
  const std::string message = "COMMAND, as task " + std::to_string(index) + " (" + job.tasks[index].what +
                              ") would run it: " + echo(first, 600);
  if (rc == 2) throw UsageError(message);
  throw std::runtime_error(message + " (exit " + std::to_string(rc) + ")");
}

int run_slurm(const SlurmArgs& a) {
  if (a.dir.empty()) throw UsageError("--dir: a job directory is required");
  if (a.concurrency < 0) throw UsageError("--concurrency: must be >= 0 (0: no limit)");
  if (a.cpus_per_task < 1 || a.cpus_per_task > 4096) throw UsageError("--cpus-per-task: must be in [1, 4096]");
  if (a.hold && a.wait) throw UsageError("--hold and --wait: a held array never ends by itself; give one");
  if (a.retries < 0 || a.retries > 100) throw UsageError("--retries: must be in [0, 100]");
  for (const auto& [flag, v] : {std::pair{"--partition", a.partition}, {"--mem", a.mem}, {"--time-limit", a.time_limit}})
    if (v.find_first_of(" \t\n'\"\\$`;") != std::string::npos)
      throw UsageError(std::string(flag) + ": '" + echo(v) + "' holds a character Slurm options do not");
  // Paths go into #SBATCH lines, which split at white space and read % as a file-name pattern.
  auto sbatch_safe = [](const std::string& p) { return p.find_first_of(" \t\n\r%'\"\\$`") == std::string::npos; };
  if (!sbatch_safe(a.dir))
    throw UsageError("--dir: '" + echo(a.dir) + "' holds white space, %, a quote, \\, $ or `, which #SBATCH lines cannot carry");
  if (!sbatch_safe(std::filesystem::current_path().string()))
    throw UsageError("the working directory '" + echo(std::filesystem::current_path().string()) +
                     "' holds white space, %, a quote, \\, $ or `, which #SBATCH --chdir cannot carry; run from another");
  const FarmJob job = plan_farm_job(a.command, a.chunk, a.bricks, a.dir);
  const std::filesystem::path dir(job.dir);
  // The command as the first and the last task will run it, before anything is written: a flag,
  // preset, file or range that every task would refuse is refused here, with the task's words.
  check_task_command(job, 0);
  if (job.tasks.size() > 1) check_task_command(job, job.tasks.size() - 1);
  std::vector<std::pair<std::string, std::string>> files{{"job.json", farm_job_json(job)},
                                                         {"task.sh", task_script(a, job)},
                                                         {"check.sh", check_script(a, job)}};
  if (job.kind == "bricks") files.emplace_back("merge.sh", merge_script(a, job));
  // submit.sh: the same submission by hand.
  std::string submit = "#!/bin/bash\n# Submits the job as nimbus farm slurm does (docs/farm.md).\nset -eu\n";
  submit += "array=$(sbatch --parsable " + shell_quote(job.dir + "/task.sh") + ")\narray=${array%%;*}\n";
  submit += "check=$(sbatch --parsable --dependency=afterany:$array " + shell_quote(job.dir + "/check.sh") + " $array)\ncheck=${check%%;*}\n";
  if (job.kind == "bricks")
    submit += "sbatch --parsable --dependency=afterok:$check --kill-on-invalid-dep=yes " + shell_quote(job.dir + "/merge.sh") + "\n";
  files.emplace_back("submit.sh", submit);
  checks_done();
  write_job_folder(job, files);
  std::printf("%s job of %zu task(s) (%s ... %s) in %s\n", job.kind.c_str(), job.tasks.size(), job.tasks.front().what.c_str(),
              job.tasks.back().what.c_str(), job.dir.c_str());
  if (a.dry_run) {
    std::printf("not submitted (--dry-run): run %s/submit.sh\n", job.dir.c_str());
    return 0;
  }
  if (run_line("command -v sbatch").first != 0)
    throw std::runtime_error("sbatch not found: Slurm's client (slurm-client) is not installed or not on PATH");
  const std::string last_flags = a.wait ? " --wait" : "";
  auto [rc1, out1] = run_line(std::string("sbatch --parsable") + (a.hold ? " --hold" : "") + " " + shell_quote(job.dir + "/task.sh"));
  const std::string array = job_id(out1, "task array");
  const bool check_last = job.kind != "bricks";
  auto [rc2, out2] = run_line("sbatch --parsable --dependency=afterany:" + array + (check_last ? last_flags : "") + " " +
                               shell_quote(job.dir + "/check.sh") + " " + array);
  const std::string check = job_id(out2, "check job");
  std::printf("submitted: task array %s, check %s (after any end of the array)\n", array.c_str(), check.c_str());
  std::string merge;
  int rc = rc2;
  if (!check_last) {
    auto [rc3, out3] = run_line("sbatch --parsable --dependency=afterok:" + check + " --kill-on-invalid-dep=yes" +
                                 last_flags + " " + shell_quote(job.dir + "/merge.sh"));
    merge = job_id(out3, "merge job");
    rc = rc3;
    std::printf("submitted: merge %s (after the check succeeds)\n", merge.c_str());
  }
  if (a.hold) std::printf("the array is held: scontrol release %s starts it\n", array.c_str());
  std::fflush(stdout);
  if (!a.wait) return 0;
  // Waited for the last job: show what the check (and merge) said.
  std::printf("--- check (%s/logs/check_%s.log):\n", job.dir.c_str(), check.c_str());
  // The check's report: one line a failed task; a huge log is shown by its last 1 MiB.
  const std::filesystem::path check_log = dir / "logs" / ("check_" + check + ".log");
  std::ifstream log(check_log, std::ios::binary);
  std::string report;
  std::error_code ec;
  if (std::filesystem::file_size(check_log, ec) > (1u << 20)) {
    std::printf("(the last lines of %s)\n", check_log.c_str());
    log.seekg(-std::streamoff(1u << 20), std::ios::end);
  }
  report.resize(1u << 20);
  log.read(report.data(), std::streamsize(report.size()));
  report.resize(static_cast<std::size_t>(log.gcount()));
  std::fwrite(report.data(), 1, report.size(), stdout);
  if (!merge.empty()) std::printf("--- merge: %s\n", last_line(dir / "logs" / ("merge_" + merge + ".log")).c_str());
  return rc == 0 ? 0 : 1;
}

int run_check(const CheckArgs& a) {
  const FarmJob job = read_farm_job(a.dir);
  int failed = 0;
  for (std::size_t i = 0; i < job.tasks.size(); ++i) {
    const std::vector<std::string> problems = check_task_outputs(job, int(i));
    if (problems.empty()) continue;
    ++failed;
    std::string line = "task " + std::to_string(i) + " (" + job.tasks[i].what + "): ";
    for (std::size_t k = 0; k < problems.size(); ++k) line += (k ? "; " : "") + problems[k];
    if (!a.array_job.empty()) {
      const std::filesystem::path log =
          std::filesystem::path(job.dir) / "logs" / ("task_" + a.array_job + "_" + std::to_string(i) + ".log");
      std::error_code ec;
      line += std::filesystem::exists(std::filesystem::symlink_status(log, ec)) ? "; log " + echo(log.string(), 300) + ": " + last_line(log)
                                           : "; no log (the task never ran: cancelled before it started)";
    }
    std::printf("%s\n", line.c_str());
  }
  if (failed) {
    std::printf("nimbus farm check: %d of %zu task(s) failed: their outputs are missing or unreadable\n", failed,
                job.tasks.size());
    return 1;
  }
  std::printf("nimbus farm check: all %zu task(s) complete, every output present and readable\n", job.tasks.size());
  return 0;
}

}  // namespace

void add_farm_command(CLI::App& app, Action& action) {
  CLI::App* farm = app.add_subcommand("farm", "Run generate or render on a scheduler: frames or bricks as a job array");
  farm->require_subcommand(1);

  auto s = std::make_shared<SlurmArgs>();
  CLI::App* slurm = farm->add_subcommand("slurm", "Write and submit a Slurm job array: nimbus farm slurm --dir D [options] -- COMMAND");
  slurm->add_option("--dir", s->dir, "job directory: scripts, job.json, logs/ (one per task), bricks/")->required();
  slurm->add_option("--concurrency", s->concurrency, "tasks running at once (%N of --array); 0: no limit")->capture_default_str();
  slurm->add_option("--chunk", s->chunk, "frames per task")->capture_default_str();
  slurm->add_option("--bricks", s->bricks, "a brick job: N or AxBxC bricks of generate's field, then nimbus merge to its -o");
  slurm->add_option("--partition", s->partition, "Slurm partition");
  slurm->add_option("--mem", s->mem, "memory per task, as Slurm's --mem (e.g. 4G)");
  slurm->add_option("--time-limit", s->time_limit, "time limit per task, as Slurm's --time (e.g. 30:00)");
  slurm->add_option("--cpus-per-task", s->cpus_per_task, "CPUs per task")->capture_default_str();
  slurm->add_option("--retries", s->retries, "times a failed task runs again before it counts as failed")->capture_default_str();
  slurm->add_flag("--dry-run", s->dry_run, "write the scripts (and submit.sh) without submitting");
  slurm->add_flag("--hold", s->hold, "submit the array held (scontrol release ID starts it)");
  slurm->add_flag("--wait", s->wait, "wait for the last job, print the check, exit 1 when a task failed");
  slurm->add_option("COMMAND", s->command, "the nimbus command after --: generate ... or render ...")->required();
  slurm->callback([&action, s] { action = [s] { return run_slurm(*s); }; });

  auto c = std::make_shared<CheckArgs>();
  CLI::App* check = farm->add_subcommand("check", "List the tasks of a farm job whose outputs are missing or unreadable");
  check->add_option("DIR", c->dir, "the job directory of nimbus farm slurm")->required();
  check->add_option("--array-job", c->array_job, "the array's Slurm job id (names the task logs)");
  check->callback([&action, c] { action = [c] { return run_check(*c); }; });
}

}  // namespace nimbus::cli
