// Frames and bricks for a farm, as the command line offers them: sequences named alike by
// generate and render; a job-array task's frames (--frame-from-env, --chunk) equal to the
// sequential run's byte for byte; --start-frame; nimbus merge; nimbus farm slurm --dry-run's
// scripts and nimbus farm check. (The same on a real Slurm cluster: tests/farm.)
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "nimbus/volume/vdb_read.hpp"
#include "support/run_nimbus.hpp"

namespace {

using nimbus::test::run_command;
using nimbus::test::run_nimbus;
namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  auto d = fs::temp_directory_path() / ("nimbus_farm_" + std::to_string(::getpid())) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// nimbus with SLURM_ARRAY_TASK_ID=task.
nimbus::test::RunResult run_task(int task, const std::string& args) {
  return run_command("SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " " + NIMBUS_BINARY + " " + args);
}

double meta_time(const fs::path& p) {
  for (const auto& [k, v] : nimbus::volume::read_volume_vdb(p, nimbus::volume::VdbReadOptions{}).metadata)
    if (k == "time") return std::get<double>(v);
  return -1;
}

TEST(FarmCli, GenerateAndRenderNameSequencesAlike) {
  const auto d = temp_dir("names");
  auto r = run_nimbus("generate --preset cumulus-humilis --voxel-size 20 --frames 1-2 -o " + (d / "seq.%04d.vdb").string());
  ASSERT_EQ(r.code, 0) << r.output;
  r = run_nimbus("generate --preset cumulus-humilis --voxel-size 20 --frames 3-3 -o " + (d / "seq.vdb").string());
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* f : {"seq.0001.vdb", "seq.0002.vdb", "seq.0003.vdb"}) EXPECT_TRUE(fs::exists(d / f)) << f;
  const std::string render = "render --preset cumulus-humilis --voxel-size 40 --res 32x24 --ms-photons 4000 --frames 7-7 -o ";
  r = run_nimbus(render + (d / "r.%04d.exr").string());
  ASSERT_EQ(r.code, 0) << r.output;
  r = run_nimbus(render + (d / "p.exr").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(fs::exists(d / "r.0007.exr"));
  EXPECT_TRUE(fs::exists(d / "p.0007.exr"));
  // A frame field without --frames would name a file "%04d": refused by both commands.
  r = run_nimbus("render --preset cumulus-humilis --voxel-size 40 --res 32x24 -o " + (d / "one.%04d.exr").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("holds a frame field but no --frames"), std::string::npos) << r.output;
  int files = 0;
  for (const auto& e : fs::directory_iterator(d)) {
    EXPECT_EQ(e.path().filename().string().find('%'), std::string::npos) << e.path();
    ++files;
  }
  EXPECT_EQ(files, 5);
}

TEST(FarmCli, TasksInAnyOrderWriteTheSequentialRunsFilesByteForByte) {
  const auto d = temp_dir("tasks");
  const std::string gen = "generate --preset cumulus-humilis --voxel-size 20 --frames 1-5 --fps 6 ";
  auto r = run_nimbus(gen + "-o " + (d / "seq.%04d.vdb").string());
  ASSERT_EQ(r.code, 0) << r.output;
  for (int task : {2, 0, 1}) {  // chunks of 2: {1, 2}, {3, 4}, {5}
    r = run_task(task, gen + "--frame-from-env SLURM_ARRAY_TASK_ID --chunk 2 -o " + (d / "task.%04d.vdb").string());
    ASSERT_EQ(r.code, 0) << r.output;
    if (task == 2) {  // the last task writes its one frame only
      EXPECT_TRUE(fs::exists(d / "task.0005.vdb"));
      EXPECT_FALSE(fs::exists(d / "task.0001.vdb"));
    }
  }
  for (int f = 1; f <= 5; ++f) {
    char a[32], b[32];
    std::snprintf(a, sizeof a, "seq.%04d.vdb", f);
    std::snprintf(b, sizeof b, "task.%04d.vdb", f);
    EXPECT_EQ(bytes(d / a), bytes(d / b)) << "frame " << f;
  }
  // A render too: the image and its metadata (no timings) are a function of the frame.
  const std::string render =
      "render --preset cumulus-humilis --voxel-size 40 --res 32x24 --ms-photons 4000 --frames 1-2 ";
  r = run_nimbus(render + "-o " + (d / "seq.%04d.exr").string() + " --preview " + (d / "seq.%04d.png").string());
  ASSERT_EQ(r.code, 0) << r.output;
  for (int task : {1, 0}) {
    r = run_task(task, render + "--frame-from-env SLURM_ARRAY_TASK_ID -o " + (d / "task.%04d.exr").string() + " --preview " +
                           (d / "task.%04d.png").string());
    ASSERT_EQ(r.code, 0) << r.output;
  }
  for (const char* ext : {".exr", ".png"})
    for (int f = 1; f <= 2; ++f)
      EXPECT_EQ(bytes(d / ("seq.000" + std::to_string(f) + ext)), bytes(d / ("task.000" + std::to_string(f) + ext)))
          << "frame " << f << ext;
}

TEST(FarmCli, StartFrameIsTimeZero) {
  const auto d = temp_dir("start");
  auto r = run_nimbus("generate --preset cumulus-humilis --voxel-size 20 --frames 1001-1002 --fps 24 --start-frame 1001 -o " +
                      (d / "s.vdb").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(meta_time(d / "s.1001.vdb"), 0.0);
  EXPECT_DOUBLE_EQ(meta_time(d / "s.1002.vdb"), 1.0 / 24.0);
  r = run_nimbus("generate --preset cumulus-humilis --voxel-size 20 --frames 2-2 --fps 24 -o " + (d / "z.vdb").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_DOUBLE_EQ(meta_time(d / "z.0002.vdb"), 2.0 / 24.0);  // the default start frame is 0
}

TEST(FarmCli, TaskIdsAndFrameFlagsAreCheckedNamingTheInput) {
  const auto d = temp_dir("bad");
  const std::string gen = "generate --preset cumulus-humilis --voxel-size 20 -o " + (d / "f.%04d.vdb").string() + " ";
  struct Case {
    std::string env, args, names;
  };
  for (const Case& c : std::vector<Case>{
           {"", "--frames 1-4 --frame-from-env NIMBUS_TEST_NO_SUCH_VAR", "NIMBUS_TEST_NO_SUCH_VAR is not set"},
           {"SLURM_ARRAY_TASK_ID=abc ", "--frames 1-4 --frame-from-env SLURM_ARRAY_TASK_ID", "'abc' is not a task id"},
           {"SLURM_ARRAY_TASK_ID=-1 ", "--frames 1-4 --frame-from-env SLURM_ARRAY_TASK_ID", "is not a task id"},
           {"SLURM_ARRAY_TASK_ID=2 ", "--frames 1-4 --chunk 2 --frame-from-env SLURM_ARRAY_TASK_ID", "task ids 0-1"},
           {"", "--frames 1-4 --chunk 2", "--chunk: needs --frame-from-env"},
           {"SLURM_ARRAY_TASK_ID=0 ", "--time 1 --frame-from-env SLURM_ARRAY_TASK_ID", "--frame-from-env: needs --frames"},
           {"", "--frames 1-4 --chunk 0", "--chunk: must be at least 1"},
           {"", "--time 1 --start-frame 1001", "--start-frame: needs --frames"},
           {"", "--time 1", "holds a frame field but no --frames"},
           {"", "--frames 1-2 --brick 0/2", "--brick: a brick is of one time"},
       }) {
    SCOPED_TRACE(c.args);
    const auto r = run_command(c.env + NIMBUS_BINARY + " " + gen + c.args);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find(c.names), std::string::npos) << r.output;
  }
  EXPECT_TRUE(fs::is_empty(d));
}

TEST(FarmCli, MergeJoinsBricksIntoTheOneProcessFileAndNamesABadSet) {
  const auto d = temp_dir("merge");
  const std::string field = "generate --preset cumulus-field --voxel-size 40 ";
  auto r = run_nimbus(field + "-o " + (d / "whole.vdb").string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::string bricks;
  for (int i = 0; i < 4; ++i) {
    const std::string b = (d / ("b" + std::to_string(i) + ".vdb")).string();
    r = run_nimbus(field + "--brick " + std::to_string(i) + "/2x2x1 -o " + b);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("peak memory"), std::string::npos) << r.output;  // memory per brick is reported
    bricks += " " + b;
  }
  r = run_nimbus("merge" + bricks + " -o " + (d / "merged.vdb").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(bytes(d / "merged.vdb"), bytes(d / "whole.vdb"));
  r = run_nimbus("merge " + (d / "b0.vdb").string() + " " + (d / "b1.vdb").string() + " -o " + (d / "m.vdb").string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("missing 2 of the 4 bricks of 2x2x1"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(d / "m.vdb"));
  r = run_nimbus("merge" + bricks + " -o " + (d / "b0.vdb").string());
  EXPECT_EQ(r.code, 2) << r.output;
  r = run_nimbus(field + "--brick 4/2x2x1 -o " + (d / "x.vdb").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("brick 4 of 2x2x1 does not exist"), std::string::npos) << r.output;
  r = run_nimbus(field + "--brick 0/64x1x1 -o " + (d / "x.vdb").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("64 bricks along x"), std::string::npos) << r.output;
}

TEST(FarmCli, DryRunScriptsRunTasksAndCheckListsMissingOrDamagedOutputsByIndex) {
  const auto d = temp_dir("dry");
  const auto job = d / "job";
  const std::string out = (d / "f.%04d.vdb").string();
  // A sound frame 3 left by an earlier run: the job's check must not count it as this job's.
  ASSERT_EQ(run_task(1, "generate --preset cumulus-humilis --voxel-size 20 --frames 1-5 --frame-from-env SLURM_ARRAY_TASK_ID "
                       "--chunk 2 -o " + out).code, 0);
  fs::remove(d / "f.0004.vdb");
  auto r = run_nimbus("farm slurm --dir " + job.string() + " --concurrency 3 --chunk 2 --retries 0 --dry-run -- generate "
                      "--preset cumulus-humilis --voxel-size 20 --frames 1-5 -o " + out);
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string script = bytes(job / "task.sh");
  EXPECT_NE(script.find("#SBATCH --array=0-2%3"), std::string::npos) << script;
  EXPECT_NE(script.find("'--frame-from-env' 'SLURM_ARRAY_TASK_ID' '--chunk' '2'"), std::string::npos) << script;
  EXPECT_NE(bytes(job / "submit.sh").find("--dependency=afterany:$array"), std::string::npos);
  // Tasks 0 and 2 run (the script itself, as Slurm would run it); task 1 never does.
  for (int task : {0, 2}) {
    const auto t = run_command("SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " bash " + (job / "task.sh").string());
    ASSERT_EQ(t.code, 0) << t.output;
  }
  r = run_nimbus("farm check " + job.string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("task 1 (frames 3-4): stale " + (d / "f.0003.vdb").string() + " (written before this job); missing " +
                          (d / "f.0004.vdb").string()),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("task 0"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 of 3 task(s) failed"), std::string::npos) << r.output;
  // Task 1 runs, then frame 5 is damaged (cut short): unreadable, reported under its task.
  ASSERT_EQ(run_command("SLURM_ARRAY_TASK_ID=1 bash " + (job / "task.sh").string()).code, 0);
  fs::resize_file(d / "f.0005.vdb", fs::file_size(d / "f.0005.vdb") / 2);
  r = run_nimbus("farm check " + job.string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("task 2 (frame 5): unreadable " + (d / "f.0005.vdb").string()), std::string::npos) << r.output;
  ASSERT_EQ(run_command("SLURM_ARRAY_TASK_ID=2 bash " + (job / "task.sh").string()).code, 0);
  r = run_nimbus("farm check " + job.string());
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("all 3 task(s) complete"), std::string::npos) << r.output;
}

TEST(FarmCli, CommandsTheFarmCannotCutAreUsageErrors) {
  const auto d = temp_dir("usage");
  const std::string farm = "farm slurm --dir " + (d / "job").string() + " --dry-run ";
  struct Case {
    std::string args, names;
  };
  for (const Case& c : std::vector<Case>{
           {"-- generate --preset cumulus-humilis -o f.vdb", "needs --frames"},
           {"-- generate --preset cumulus-humilis --frames 1-2 --frame-from-env X -o f.vdb", "--frame-from-env is set by the farm"},
           {"-- generate --preset cumulus-humilis --frames 1-2", "needs -o"},
           {"-- info f.vdb", "'info' is not a command the farm cuts"},
           {"--bricks 2x2x1 -- render --preset cumulus-field -o f.exr", "only generate writes bricks"},
           {"--bricks 2x2x1 -- generate --preset cumulus-field --frames 1-2 -o f.%04d.vdb", "a brick job is of one time"},
           {"--bricks 0 -- generate --preset cumulus-field -o f.vdb", "1 to 4096 bricks"},
           {"--hold --wait -- generate --preset cumulus-humilis --frames 1-2 -o f.vdb", "--hold and --wait"},
           {"--mem '4G;rm' -- generate --preset cumulus-humilis --frames 1-2 -o f.vdb", "--mem"},
       }) {
    SCOPED_TRACE(c.args);
    const auto r = run_nimbus(farm + c.args);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find(c.names), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(d / "job"));
  const auto spaced = run_nimbus("farm slurm --dry-run --dir '" + (d / "a job").string() +
                                 "' -- generate --preset cumulus-humilis --frames 1-2 -o f.vdb");
  EXPECT_EQ(spaced.code, 2) << spaced.output;
  EXPECT_NE(spaced.output.find("--dir: '"), std::string::npos) << spaced.output;
  EXPECT_FALSE(fs::exists(d / "a job"));
  const auto r = run_nimbus("farm check " + (d / "nothing").string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("job.json"), std::string::npos) << r.output;
}

}  // namespace
