// The farm job model of the app library (nimbus/app/farm_job.hpp), called directly: a command cut
// into tasks that cover every frame or brick exactly once, job.json round trips, task command
// lines, and the check of each task's outputs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "nimbus/app/farm_job.hpp"
#include "nimbus/app/shell.hpp"
#include "nimbus/app/usage_error.hpp"
#include "support/vdb_fixtures.hpp"

namespace nimbus::test {
namespace {

using app::FarmJob;
using app::UsageError;

std::vector<std::string> words(std::initializer_list<const char*> w) { return {w.begin(), w.end()}; }

// Every output of every task, in task order.
std::vector<std::string> all_outputs(const FarmJob& job) {
  std::vector<std::string> out;
  for (const app::FarmTask& t : job.tasks) out.insert(out.end(), t.outputs.begin(), t.outputs.end());
  return out;
}

TEST(AppFarmJob, FramesInChunksCoverEveryFrameOnceInOrder) {
  TempDir dir;
  for (const int chunk : {1, 3, 4, 10, 11}) {
    const FarmJob job = app::plan_farm_job(
        words({"generate", "--preset", "cumulus", "--frames", "1001-1010", "-o", "out/c.%04d.vdb"}), chunk, "",
        dir.path / "job");
    EXPECT_EQ(job.kind, "frames");
    EXPECT_EQ(job.first, 1001);
    EXPECT_EQ(job.last, 1010);
    EXPECT_EQ(job.tasks.size(), std::size_t((10 + chunk - 1) / chunk)) << "chunk " << chunk;
    std::vector<std::string> expected;
    for (int f = 1001; f <= 1010; ++f) expected.push_back("out/c." + std::to_string(f) + ".vdb");
    EXPECT_EQ(all_outputs(job), expected) << "chunk " << chunk;
    for (std::size_t t = 0; t + 1 < job.tasks.size(); ++t) EXPECT_EQ(job.tasks[t].outputs.size(), std::size_t(chunk));
  }
}

TEST(AppFarmJob, APreviewAddsItsFileToEachFrameAndTheLastTaskIsShort) {
  TempDir dir;
  const FarmJob job = app::plan_farm_job(
      words({"render", "in.%04d.vdb", "--frames", "1-5", "-o", "r.exr", "--preview", "p.%03d.png"}), 2, "",
      dir.path / "job");
  ASSERT_EQ(job.tasks.size(), 3u);
  EXPECT_EQ(job.tasks[0].what, "frames 1-2");
  EXPECT_EQ(job.tasks[2].what, "frame 5");
  EXPECT_EQ(job.tasks[2].outputs, words({"r.0005.exr", "p.005.png"}));
}

TEST(AppFarmJob, BricksAreOneTaskEachInsideTheJobDirectory) {
  TempDir dir;
  const FarmJob job = app::plan_farm_job(words({"generate", "--preset", "cumulus", "-o", "joined.vdb"}), 1, "2x3x1",
                                         dir.path / "job");
  EXPECT_EQ(job.kind, "bricks");
  EXPECT_EQ(job.merge_output, "joined.vdb");
  ASSERT_EQ(job.tasks.size(), 6u);
  std::set<std::string> unique;
  for (const app::FarmTask& t : job.tasks) {
    ASSERT_EQ(t.outputs.size(), 1u);
    EXPECT_EQ(std::filesystem::path(t.outputs[0]).parent_path(), std::filesystem::path(job.dir) / "bricks");
    unique.insert(t.outputs[0]);
  }
  EXPECT_EQ(unique.size(), 6u);
  // The task's arguments drop -o (each task writes its brick), in either spelling.
  for (const char* o : {"-o", "--output"}) {
    FarmJob j = job;
    j.command = words({"generate", "--preset", "cumulus", o, "joined.vdb", "--seed", "3"});
    EXPECT_EQ(app::task_arguments(j), words({"generate", "--preset", "cumulus", "--seed", "3"}));
  }
  FarmJob j = job;
  j.command = words({"generate", "--output=joined.vdb", "--seed", "3"});
  EXPECT_EQ(app::task_arguments(j), words({"generate", "--seed", "3"}));
}

TEST(AppFarmJob, FrameTasksReadTheirIdFromTheArrayVariable) {
  TempDir dir;
  const FarmJob job =
      app::plan_farm_job(words({"generate", "--frames", "1-8", "-o", "a.vdb"}), 4, "", dir.path / "job");
  EXPECT_EQ(app::task_arguments(job), words({"generate", "--frames", "1-8", "-o", "a.vdb", "--frame-from-env",
                                             "SLURM_ARRAY_TASK_ID", "--chunk", "4"}));
}

TEST(AppFarmJob, InconsistentJobsAreUsageErrorsNamingTheInput) {
  TempDir dir;
  const auto refused = [&](std::vector<std::string> command, int chunk, const std::string& bricks,
                           const std::string& named) {
    try {
      app::plan_farm_job(command, chunk, bricks, dir.path / "job");
      ADD_FAILURE() << "accepted; expected a refusal naming " << named;
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find(named), std::string::npos) << e.what();
    }
  };
  refused({}, 1, "", "COMMAND");
  refused(words({"view", "a.vdb", "-o", "x"}), 1, "", "'view'");
  refused(words({"generate", "--frames", "1-3"}), 1, "", "-o");
  refused(words({"generate", "--frames", "1-3", "-o", "a.vdb", "--chunk", "2"}), 1, "", "--chunk");
  refused(words({"generate", "--frames", "1-3", "-o", "a%099d.vdb"}), 1, "", "COMMAND -o");
  refused(words({"generate", "-o", "a.vdb"}), 1, "", "--frames");
  refused(words({"generate", "--frames", "3-1", "-o", "a.vdb"}), 1, "", "--frames");
  refused(words({"generate", "--frames", "1-3", "-o", "a.vdb"}), 0, "", "--chunk");
  refused(words({"generate", "--frames", "1-200000", "-o", "a.vdb"}), 1, "", "100000");
  refused(words({"render", "in.vdb", "-o", "a.vdb"}), 1, "2", "only generate");
  refused(words({"generate", "--frames", "1-3", "-o", "a.vdb"}), 1, "2", "--bricks");
  refused(words({"generate", "-o", "a.%04d.vdb"}), 1, "2", "frame field");
  refused(words({"generate", "-o", "a.vdb"}), 1, "0", "--bricks");
  refused(words({"generate", "-o", "a.vdb"}), 1, "17x17x17", "--bricks");
}

TEST(AppFarmJob, JobJsonRoundTripsEveryFieldAndTheTasks) {
  TempDir dir;
  for (const std::string& bricks : {std::string(), std::string("2x2x1")}) {
    std::vector<std::string> command = words({"generate", "--preset", "cumulus", "-o", "it's \"quoted\".vdb"});
    if (bricks.empty()) command.insert(command.end(), {"--frames", "-3-4"});
    const FarmJob job = app::plan_farm_job(command, bricks.empty() ? 3 : 1, bricks, dir.path / "job");
    std::filesystem::create_directories(job.dir);
    std::ofstream(std::filesystem::path(job.dir) / "job.json") << app::farm_job_json(job);
    const FarmJob back = app::read_farm_job(job.dir);
    EXPECT_EQ(back.kind, job.kind);
    EXPECT_EQ(back.nimbus, job.nimbus);
    EXPECT_EQ(back.workdir, job.workdir);
    EXPECT_EQ(back.dir, job.dir);
    EXPECT_EQ(back.command, job.command);
    EXPECT_EQ(back.chunk, job.chunk);
    EXPECT_EQ(back.bricks, job.bricks);
    EXPECT_EQ(back.merge_output, job.merge_output);
    EXPECT_EQ(back.first, job.first);
    EXPECT_EQ(back.last, job.last);
    EXPECT_EQ(back.output, job.output);
    EXPECT_EQ(back.preview, job.preview);
    EXPECT_EQ(all_outputs(back), all_outputs(job));
    EXPECT_TRUE(back.submitted.has_value());
  }
}

TEST(AppFarmJob, ATamperedJobJsonIsRefusedNamingTheFile) {
  TempDir dir;
  const FarmJob job = app::plan_farm_job(words({"generate", "--frames", "1-4", "-o", "a.vdb"}), 1, "", dir.path);
  std::string text = app::farm_job_json(job);
  const std::size_t at = text.find("\"frames\"");
  ASSERT_NE(at, std::string::npos);
  const std::size_t open = text.find('[', at), close = text.find(']', at);
  text.replace(open, close - open + 1, "[4, 1]");  // reversed
  std::ofstream(dir.path / "job.json") << text;
  try {
    app::read_farm_job(dir.path);
    ADD_FAILURE() << "a reversed range was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("job.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--frames"), std::string::npos) << e.what();
  }
}

TEST(AppFarmJob, OutputChecksFindMissingEmptyStaleAndForeignFiles) {
  TempDir dir;
  FarmJob job = app::plan_farm_job(words({"render", "in.vdb", "--frames", "1-4", "-o", "f.png"}), 1, "", dir.path);
  job.workdir = dir.path.string();  // relative outputs resolve here
  // Frame 1 missing; 2 empty; 3 a PNG signature; 4 not a PNG.
  std::ofstream(dir.path / "f.0002.png");
  std::ofstream(dir.path / "f.0003.png", std::ios::binary) << std::string("\x89PNG\r\n\x1a\n", 8) << "rest";
  std::ofstream(dir.path / "f.0004.png") << "GIF89a";
  job.submitted = std::filesystem::file_time_type::min();
  const auto first_word = [&](int task) {
    const std::vector<std::string> p = app::check_task_outputs(job, task);
    return p.empty() ? std::string("complete") : p[0].substr(0, p[0].find(' '));
  };
  EXPECT_EQ(first_word(0), "missing");
  EXPECT_EQ(first_word(1), "empty");
  EXPECT_EQ(first_word(2), "complete");
  EXPECT_EQ(first_word(3), "not");
  // The same good file, older than the job's submission, is left from an earlier run.
  job.submitted = std::filesystem::last_write_time(dir.path / "f.0003.png") + std::chrono::seconds(5);
  EXPECT_EQ(first_word(2), "stale");
}

// Whatever bytes a word holds, the shell hands it to the program as that one word.
TEST(AppShell, QuotedWordsReachTheProgramUnchanged) {
  for (const std::string word : {"plain", "two words", "it's", "'", "''", "$HOME `id` \\ \" ; | &", "", "a\nb"}) {
    const app::ShellResult r = app::run_shell("printf '%s|' " + app::shell_quote(word));
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(r.output, word + "|") << app::shell_quote(word);
  }
  const app::ShellResult fail = app::run_shell("exit 7");
  EXPECT_EQ(fail.exit_code, 7);
  EXPECT_EQ(fail.signal, 0);
  const app::ShellResult killed = app::run_shell("kill -TERM $$");
  EXPECT_EQ(killed.exit_code, -1);
  EXPECT_EQ(killed.signal, 15);
}

}  // namespace
}  // namespace nimbus::test
