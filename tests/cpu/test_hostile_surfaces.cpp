// Hostile input to the surfaces added after the first campaign: viewer scripts and sky files,
// view states and `render --view-state`, sequence patterns, bricks and merge, the farm, camera
// and quality flags. Each class of fault the second campaign found has a test here: format
// strings, inputs overwritten, errors that exited 0, silent nonsense, farm jobs every task would
// refuse, and messages that echoed raw or unbounded text. Refusals are table rows (one stderr
// line, the exit code, nothing on stdout, the directory unchanged: support/hostile_table.hpp);
// the rest run a command and check what it left.
#include <gtest/gtest.h>
#include <png.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/hostile_table.hpp"
#include "support/run_split.hpp"

namespace nimbus::test {
namespace {

namespace fs = std::filesystem;

using Case = HostileCase;

void write_file(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

// A 2x2 grey PNG, as a coverage map.
void write_grey_png(const fs::path& p) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = 2;
  image.height = 2;
  image.format = PNG_FORMAT_GRAY;
  const unsigned char grey[4] = {0, 128, 255, 64};
  png_image_write_to_file(&image, p.c_str(), 0, grey, 0, nullptr);
  png_image_free(&image);
}

bool has_control_character(const std::string& text) {
  return std::any_of(text.begin(), text.end(), [](char c) {
    return c != '\n' && (static_cast<unsigned char>(c) < 0x20 || c == 0x7f);
  });
}

// A view state of one small preset cloud; `extra` is spliced into its top level, `cloud` into the
// cloud's object.
std::string state_json(const std::string& extra = "", const std::string& cloud = R"("preset": "cumulus-humilis")") {
  return R"({"nimbus": "view state", "sky": {"clouds": [{)" + cloud + R"(}]})" + (extra.empty() ? "" : ", " + extra) + "}";
}

class HostileSurfaces : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() / ("nimbus_surfaces_" + std::to_string(::getpid())));
    const fs::path& d = *dir_;
    fs::remove_all(d);
    fs::create_directories(d / "sub");
    const std::string ds = d.string();
    write_file(d / "script.json", R"({"frames": 1})");
    write_file(d / "sky.json", R"({"clouds": [{"preset": "cumulus-humilis"}]})");
    write_file(d / "state.json", state_json());
    write_file(d / "file", "a regular file, not a folder");
    ::mkfifo((d / "fifo").c_str(), 0600);
    fs::create_symlink("/dev/null", d / "null.json");
    // Format strings where a file name goes.
    for (const auto& [name, pattern] : {std::pair<std::string, std::string>{"s", "%s%s%s%s"}, {"n", "%n%n"}, {"wide", "%99999999d"}}) {
      write_file(d / ("sky_fmt_" + name + ".json"), R"({"clouds": [{"file": ")" + pattern + R"("}]})");
      write_file(d / ("state_fmt_" + name + ".json"), state_json("", R"("file": ")" + pattern + R"(")"));
    }
    // Scripts that would write over an input or a special file.
    write_file(d / "record_self.json", R"({"frames": 1, "record": ")" + ds + R"(/record_self.json"})");
    write_file(d / "record_fifo.json", R"({"frames": 1, "record": ")" + ds + R"(/fifo"})");
    write_file(d / "record_state.json", R"({"frames": 1, "record": ")" + ds + R"(/state.json"})");
    write_file(d / "save_sky_input.json", R"({"frames": 1, "events": [{"frame": 0, "save_sky": ")" + ds + R"(/sky.json"}]})");
    write_file(d / "save_sky_link.json", R"({"frames": 1, "events": [{"frame": 0, "save_sky": ")" + ds + R"(/null.json"}]})");
    write_file(d / "save_sky_nodir.json",
               R"({"frames": 1, "events": [{"frame": 0, "save_sky": ")" + ds + R"(/file/sky.json"}]})");
    // Nonsense that was silently accepted.
    write_file(d / "event_late.json", R"({"frames": 3, "events": [{"frame": 5, "key": "space"}]})");
    write_file(d / "state_scale.json", state_json(R"("renderer": {"render_scale": 0.01})"));
    write_file(d / "state_fov.json", state_json(R"("camera": {"fov": 1e-4})"));
    write_file(d / "state_fov_huge.json", state_json(R"("camera": {"fov": 1e300})"));
    write_file(d / "state_extinction.json", state_json(R"("optics": {"extinction": 1e300})"));
    write_file(d / "state_sky_fifo.json", state_json("", R"("file": ")" + ds + R"(/fifo")"));
    write_file(d / "state_sky_dir.json", state_json("", R"("file": ")" + ds + R"(/sub")"));
    // Messages: a key holding an escape sequence, and a key of 100 kB.
    write_file(d / "key_escape.json", "{\"frames\": 1, \"\\u001b[31mred\": 1}");
    write_file(d / "key_long.json", R"({"frames": 1, ")" + std::string(100000, 'k') + R"(": 1})");
    write_file(d / "sky_key_escape.json", "{\"clouds\": [{\"preset\": \"cumulus-humilis\", \"\\u001b]0;title\\u0007\": 1}]}");
    write_file(d / "null_cloud.json", R"({"cloud": null})");
    // Files named inside other inputs: a coverage map (a sky file's, relative to it; a params
    // file's, relative to it; a view state's) and a sky's file cloud.
    write_grey_png(d / "map.png");
    write_file(d / "sky_map.json",
               R"({"clouds": [{"preset": "cumulus-humilis", "overrides": {"coverage_map": "map.png"}}]})");
    write_file(d / "params_map.json", R"({"coverage_map": "map.png"})");
    write_file(d / "state_map.json",
               state_json("", R"("preset": "cumulus-humilis", "overrides": {"coverage_map": ")" + ds + R"(/map.png"})"));
    write_file(d / "save_sky_map.json", R"({"frames": 1, "events": [{"frame": 0, "save_sky": ")" + ds + R"(/map.png"}]})");
    write_file(d / "record_out.json", R"({"frames": 1, "record": ")" + ds + R"(/out_state.json"})");
    // A farm job folder with something other than a regular file where its files go.
    fs::create_directories(d / "job_fifo");
    ::mkfifo((d / "job_fifo" / "task.sh").c_str(), 0600);
    fs::create_directories(d / "job_link");
    fs::create_symlink("/dev/null", d / "job_link" / "check.sh");
    fs::create_directories(d / "job_logs_file");
    write_file(d / "job_logs_file" / "logs", "not a folder");
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  static void expect_refused(const std::vector<Case>& cases) { test::expect_refused(*dir_, cases); }
  static fs::path* dir_;
};
fs::path* HostileSurfaces::dir_ = nullptr;

const std::vector<std::string> kScript = {"view", "--headless", "--script"};
const std::vector<std::string> kSteamFrames = {"generate", "--preset", "steam", "--voxel-size", "0.05"};

std::vector<std::string> with(std::vector<std::string> head, const std::vector<std::string>& tail) {
  head.insert(head.end(), tail.begin(), tail.end());
  return head;
}

// A file name or pattern was handed to printf as its format: "%s%s" crashed, "%n" wrote memory,
// "%99999999d" ran until killed. Every pattern is now parsed once; only %d and %0Nd (N <= 9) pass.
TEST_F(HostileSurfaces, NoUserTextIsEverAFormat) {
  const std::string field = "a frame field is %d or %0Nd with N from 1 to 9";
  expect_refused({
      {with(kScript, {"{d}/script.json", "{d}/x%0s.vdb"}), 2, field},
      {with(kScript, {"{d}/script.json", "{d}/x%s%n.vdb"}), 2, field},
      {with(kScript, {"{d}/script.json", "--sky", "{d}/sky_fmt_s.json"}), 2, ".clouds[0].file '%s%s%s%s': " + field},
      {with(kScript, {"{d}/script.json", "--sky", "{d}/sky_fmt_n.json"}), 2, ".clouds[0].file '%n%n': " + field},
      {with(kScript, {"{d}/script.json", "--sky", "{d}/sky_fmt_wide.json"}), 2, ".clouds[0].file '%99999999d': " + field},
      {with(kScript, {"{d}/script.json", "--state", "{d}/state_fmt_n.json"}), 2, ".clouds[0].file '%n%n'"},
      {{"render", "--view-state", "{d}/state_fmt_s.json", "-o", "{d}/o.exr"}, 2, ".clouds[0].file '%s%s%s%s'"},
      {{"render", "--view-state", "{d}/state_fmt_wide.json", "-o", "{d}/o.exr"}, 2, "'%99999999d': " + field},
      {with(kSteamFrames, {"--frames", "7", "-o", "{d}/a%099d.vdb"}), 2, "-o '{d}/a%099d.vdb': " + field},
      {with(kSteamFrames, {"--frames", "7", "-o", "{d}/a%04d%04d.vdb"}), 2, "more than one %"},
      {with(kSteamFrames, {"--frames", "7", "-o", "{d}/a%%.vdb"}), 2, field},
      // One picture: a frame field in its name was written literally.
      {{"render", "--view-state", "{d}/state.json", "-o", "{d}/o.%04d.exr"}, 2, "a view state renders one picture"},
  });
}

// A script's record, its save_sky events and farm job files replaced inputs, devices, FIFOs and
// links. Each is now checked with the run's other files before any frame is drawn.
TEST_F(HostileSurfaces, WritesNeverReplaceInputsOrSpecialFiles) {
  expect_refused({
      {with(kScript, {"{d}/record_self.json"}), 2, "script record '{d}/record_self.json': is also --script"},
      {with(kScript, {"{d}/record_state.json", "--state", "{d}/state.json"}), 2,
       "script record '{d}/state.json': is also --state"},
      {with(kScript, {"{d}/record_fifo.json"}), 1, "script record '{d}/fifo': is a FIFO"},
      {with(kScript, {"{d}/save_sky_input.json", "--sky", "{d}/sky.json"}), 2, "script save_sky '{d}/sky.json': is also --sky"},
      {with(kScript, {"{d}/save_sky_link.json"}), 1, "script save_sky '{d}/null.json': is a symbolic link"},
      {{"farm", "slurm", "--dir", "{d}/job_fifo", "--dry-run", "--", "generate", "--preset", "steam", "--voxel-size", "0.05",
        "--frames", "1-2", "-o", "{d}/seq.%04d.vdb"},
       1, "task.sh': is a FIFO"},
      {{"farm", "slurm", "--dir", "{d}/job_link", "--dry-run", "--", "generate", "--preset", "steam", "--voxel-size", "0.05",
        "--frames", "1-2", "-o", "{d}/seq.%04d.vdb"},
       1, "check.sh': is a symbolic link"},
      {{"farm", "slurm", "--dir", "{d}/job_logs_file", "--dry-run", "--", "generate", "--preset", "steam", "--voxel-size",
        "0.05", "--frames", "1-2", "-o", "{d}/seq.%04d.vdb"},
       2, "logs' exists and is not a folder"},
  });
}

// A file named inside an input (a sky file's coverage map, a --params file's, a --set's, a view
// state's sky) was no input to the output checks: only the flags' own files were. `generate --sky
// k.json -o m.png` replaced the map k.json names. Every file named anywhere in a run's inputs is
// now one, and a script's record and --state-out may not be one file either.
TEST_F(HostileSurfaces, FilesNamedInsideInputsAreInputsToo) {
  const std::vector<std::string> humilis = {"generate", "--preset", "cumulus-humilis"};
  const std::vector<std::string> field = {"generate", "--preset", "cumulus-field", "--voxel-size", "200"};
  expect_refused({
      {{"generate", "--sky", "{d}/sky_map.json", "-o", "{d}/map.png"}, 2,
       "-o '{d}/map.png': is also --sky '{d}/sky_map.json' clouds[0].overrides.coverage_map"},
      {with(humilis, {"--params", "{d}/params_map.json", "-o", "{d}/map.png"}), 2, "-o '{d}/map.png': is also cloud.coverage_map"},
      {with(field, {"--set", "coverage_map={d}/map.png", "-o", "{d}/map.png"}), 2, "-o '{d}/map.png': is also cloud.coverage_map"},
      {with(field, {"--set", "coverage_map={d}/map.png", "-o", "{d}/sub/../map.png"}), 2,
       "is also cloud.coverage_map '{d}/map.png'"},
      {{"render", "--view-state", "{d}/state_map.json", "-o", "{d}/o.exr", "--preview", "{d}/map.png"}, 2,
       "--preview '{d}/map.png': is also --view-state '{d}/state_map.json' sky clouds[0].overrides.coverage_map"},
      {with(kScript, {"{d}/save_sky_map.json", "--sky", "{d}/sky_map.json"}), 2,
       "script save_sky '{d}/map.png': is also --sky '{d}/sky_map.json' clouds[0].overrides.coverage_map"},
      {with(kScript, {"{d}/save_sky_map.json", "--state", "{d}/state_map.json"}), 2,
       "script save_sky '{d}/map.png': is also --state '{d}/state_map.json' sky clouds[0].overrides.coverage_map"},
      // The record and --state-out naming one file: one would replace the other, without a word.
      {with(kScript, {"{d}/record_out.json", "--state-out", "{d}/out_state.json"}), 2,
       "script record '{d}/out_state.json': is also --state-out"},
  });
}

// Failures a scripted run found after its work, or never: each is now an error before it.
TEST_F(HostileSurfaces, ScriptedRunsRefuseWhatWouldFailLater) {
  expect_refused({
      {with(kScript, {"{d}/save_sky_nodir.json"}), 1, "script save_sky '{d}/file/sky.json'"},
      {with(kScript, {"{d}/script.json", "--screenshot-dir", "{d}/file"}), 2, "--screenshot-dir '{d}/file': is not a folder"},
      {with(kScript, {"{d}/event_late.json"}), 2, ".events[0].frame 5 is past the last frame (2; frames: 3)"},
  });
}

// Values valid alone but nonsense together, and values that framed or rendered nothing.
TEST_F(HostileSurfaces, NonsenseIsRefusedNamingTheInput) {
  expect_refused({
      {{"render", "--view-state", "{d}/state_scale.json", "--res", "64x36", "-o", "{d}/o.exr"}, 2,
       "--res 64x36 at the state's renderer.render_scale 0.01 is below one pixel"},
      {{"render", "--preset", "steam", "--voxel-size", "0.05", "--scene", "none", "--res", "8x8", "--fov", "1e-4", "-o",
        "{d}/o.exr"},
       2, "--fov: must be in [1, 179] degrees, got 0.0001"},
      {{"render", "--preset", "steam", "--voxel-size", "0.05", "--scene", "none", "--res", "8x8", "--fov", "1e-300", "-o",
        "{d}/o.exr"},
       2, "--fov: must be in [1, 179] degrees, got 1e-300"},
      {{"render", "--view-state", "{d}/state_fov.json", "-o", "{d}/o.exr"}, 2, "camera.fov: must be in [1, 179] degrees"},
      {with(kSteamFrames, {"--frames", "0-1", "--fps", "1e-300", "-o", "{d}/f.%04d.vdb"}), 2,
       "--fps: frame 1 would be at t = 1e+300 s"},
      {{"render", "--view-state", "{d}/state_extinction.json", "-o", "{d}/o.exr"}, 2,
       "optics.extinction: must be in [0, 1e+12] per metre"},
  });
}

// The farm checks the wrapped command as each task will run it, before writing anything.
TEST_F(HostileSurfaces, FarmRefusesJobsEveryTaskWouldRefuse) {
  const std::vector<std::string> slurm = {"farm", "slurm", "--dir", "{d}/job", "--dry-run", "--"};
  expect_refused({
      {with(slurm, {"generate", "--preset", "nope", "--frames", "1-2", "-o", "{d}/s.%04d.vdb"}), 2,
       "COMMAND, as task 0 (frame 1) would run it: "},
      {with(slurm, {"generate", "--preset", "steam", "--frames", "1-2", "--bogus", "-o", "{d}/s.%04d.vdb"}), 2,
       "COMMAND, as task 0 (frame 1) would run it: "},
      {with(slurm, {"generate", "--preset", "steam", "--frames", "1-2", "-o", "{d}/a.%04d.vdb", "-o", "{d}/b.%04d.vdb"}), 2,
       "COMMAND, as task 0 (frame 1) would run it: "},
      {with(slurm, {"generate", "--preset", "steam", "--params", "{d}/null_cloud.json", "--frames", "1-2", "-o",
                    "{d}/s.%04d.vdb"}),
       2, "cloud: null is not a value"},
      {with(slurm, {"generate", "--preset", "steam", "--frames", "1-20000", "-o", "{d}/s.%04d.vdb"}), 2, "add --many-frames"},
      {with(slurm, {"generate", "--preset", "steam", "--frames", "1-200000", "--many-frames", "-o", "{d}/s.%04d.vdb"}), 2,
       "--frames: 1-200000 is more than 100000 frames for one farm job"},
      {with(slurm, {"generate", "--preset", "steam", "--frames", "0-1", "--fps", "1e-300", "-o", "{d}/s.%04d.vdb"}), 2,
       "would be at t = 1e+300 s"},
      // A brick job's joined file inside its own job folder: it could be job.json, a script or a
      // brick merge reads, and the next farm slurm --dir there replaces what is in it.
      {{"farm", "slurm", "--dir", "{d}/job", "--dry-run", "--bricks", "2", "--", "generate", "--preset", "steam", "-o",
        "{d}/job/job.json"},
       2, "COMMAND -o '{d}/job/job.json': lies inside the job folder --dir '{d}/job'"},
      {{"farm", "slurm", "--dir", "{d}/job", "--dry-run", "--bricks", "2", "--", "generate", "--preset", "steam", "-o",
        "{d}/job/bricks/brick.0000.vdb"},
       2, "lies inside the job folder"},
      {{"farm", "slurm", "--dir", "{d}/sub/../job", "--dry-run", "--bricks", "2", "--", "generate", "--preset", "steam", "-o",
        "{d}/job/field.vdb"},
       2, "lies inside the job folder"},
  });
}

// Text from files reaches the terminal escaped and bounded; numbers are printed short; a file
// that is not a regular file is named for what it is.
TEST_F(HostileSurfaces, MessagesAreEscapedBoundedAndSayWhatIsWrong) {
  expect_refused({
      {with(kScript, {"{d}/key_escape.json"}), 2, ".?[31mred: unknown key"},
      {with(kScript, {"{d}/script.json", "--sky", "{d}/sky_key_escape.json"}), 2, ".clouds[0].?]0;title?: unknown key"},
      {with(kScript, {"{d}/key_long.json"}), 2, "kkk...: unknown key"},
      {{"render", "--view-state", "{d}/state_fov_huge.json", "-o", "{d}/o.exr"}, 2, "got 1e+300"},
      {{"render", "--view-state", "{d}/state_sky_fifo.json", "-o", "{d}/o.exr"}, 1, "fifo': is a FIFO, not a VDB file"},
      {{"render", "--view-state", "{d}/state_sky_dir.json", "-o", "{d}/o.exr"}, 1, "sub': is a directory, not a VDB file"},
  });
  for (const char* f : {"key_escape.json", "key_long.json"}) {
    const SplitResult r = run_nimbus_split({"view", "--headless", "--script", (*dir_ / f).string()});
    EXPECT_FALSE(has_control_character(r.err)) << r.err;
    EXPECT_LT(r.err.size(), 1100u) << f;
  }
}

// A farm job's description stays a few hundred bytes however many frames it has, and farm check
// reads it back; a job.json with escape sequences in its names prints them escaped.
TEST(HostileFarm, JobDescriptionsStayWithinTheirOwnLimitsAndPrintEscaped) {
  const fs::path d = fs::temp_directory_path() / ("nimbus_surfaces_farm_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  SplitResult r = run_nimbus_split({"farm", "slurm", "--dir", (d / "job").string(), "--dry-run", "--", "generate", "--preset",
                                    "steam", "--frames", "1-100000", "--many-frames", "-o", (d / "s.%04d.vdb").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_LT(fs::file_size(d / "job" / "job.json"), 65536u);
  r = run_nimbus_split({"farm", "check", (d / "job").string()});
  EXPECT_EQ(r.code, 1) << r.err;  // no task ran: every output is missing, and said so on stdout
  EXPECT_EQ(r.err, "");
  EXPECT_NE(r.out.find("100000 of 100000 task(s) failed"), std::string::npos) << r.out.substr(r.out.size() - 300);

  std::ifstream in(d / "job" / "job.json");
  std::stringstream text;
  text << in.rdbuf();
  std::string json = text.str();
  const std::string pattern = (d / "s.%04d.vdb").string();
  json.replace(json.rfind(pattern), pattern.size(), (d / "\\u001b[2J%04d.vdb").string());
  write_file(d / "job" / "job.json", json);
  r = run_nimbus_split({"farm", "check", (d / "job").string()});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.out.find("missing " + (d / "?[2J0001.vdb").string()), std::string::npos) << r.out.substr(0, 300);
  EXPECT_FALSE(has_control_character(r.out));
  fs::remove_all(d);
}

// A farm job whose folder cannot take one of its files leaves nothing of itself behind.
TEST(HostileFarm, AJobFolderIsWrittenWholeOrNotAtAll) {
  const fs::path d = fs::temp_directory_path() / ("nimbus_surfaces_whole_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d / "job");
  fs::create_directories(d / "job" / "submit.sh");  // a folder where the last file goes
  const SplitResult r = run_nimbus_split({"farm", "slurm", "--dir", (d / "job").string(), "--dry-run", "--", "generate",
                                          "--preset", "steam", "--frames", "1-2", "-o", (d / "s.%04d.vdb").string()});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("submit.sh': is a directory"), std::string::npos) << r.err;
  std::vector<std::string> left;
  for (const auto& e : fs::recursive_directory_iterator(d / "job")) left.push_back(e.path().filename().string());
  EXPECT_EQ(left, std::vector<std::string>{"submit.sh"});  // no job.json, task.sh, check.sh or logs/
  fs::remove_all(d);
}

// Bricks so coarse that no voxel holds cloud join into nothing, which is refused as plain
// generate refuses an empty cloud, and no file is written.
TEST(HostileFarm, BricksOfNothingMergeIntoAnError) {
  const fs::path d = fs::temp_directory_path() / ("nimbus_surfaces_bricks_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  SplitResult r = run_nimbus_split({"generate", "--preset", "steam", "--voxel-size", "1e4", "--brick", "0/1", "-o",
                                    (d / "b0.vdb").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  r = run_nimbus_split({"merge", (d / "b0.vdb").string(), "-o", (d / "whole.vdb").string()});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("hold no voxel of density >= 1e-6"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(d / "whole.vdb"));
  fs::remove_all(d);
}

// --check-only runs every check and does no work: nothing is written, exit 0; a bad input is
// still refused; and commands without it say so.
TEST(HostileFarm, CheckOnlyChecksEverythingAndWritesNothing) {
  const fs::path d = fs::temp_directory_path() / ("nimbus_surfaces_check_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  SplitResult r = run_nimbus_split({"--check-only", "generate", "--preset", "steam", "--frames", "1-3", "-o",
                                    (d / "s.%04d.vdb").string()});
  EXPECT_EQ(r.code, 0) << r.err;
  r = run_nimbus_split({"--check-only", "render", "--preset", "steam", "--voxel-size", "0.05", "--scene", "none", "--res",
                        "8x8", "-o", (d / "o.exr").string()});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::is_empty(d));
  r = run_nimbus_split({"--check-only", "generate", "--preset", "nope", "-o", (d / "s.vdb").string()});
  EXPECT_EQ(r.code, 2);
  r = run_nimbus_split({"--check-only", "info", (d / "s.vdb").string()});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--check-only: applies to generate, render, view, merge and farm, not to info"), std::string::npos)
      << r.err;
  fs::remove_all(d);
}

// Radiances beyond the half floats of the EXR are clipped there: the run says so, naming the
// flag that made them.
TEST(HostileRender, ClippedHalfFloatsAreReportedNamingTheLight) {
  const fs::path d = fs::temp_directory_path() / ("nimbus_surfaces_clip_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  const SplitResult r = run_nimbus_split({"render", "--preset", "steam", "--voxel-size", "0.05", "--scene", "none", "--res",
                                          "16x16", "--eye", "0,-0.6,0.15", "--look-at", "0,0,0.15", "--lamp", "0,-0.3,0.15",
                                          "--lamp-intensity", "1e12", "--ms-method", "octaves", "-o", (d / "o.exr").string()});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: " + (d / "o.exr").string() + ": "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("above 65504"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--lamp-intensity"), std::string::npos) << r.err;
  fs::remove_all(d);
}

// A frame too large for the device's memory: llvmpipe under the harness's 4 GiB address-space net
// runs out at --res 16384x16384 (2 GiB a half-float target). The error names the flag and size,
// not the GL call. A sanitized build has no address-space net (its shadow needs terabytes), so
// the frame would really be allocated there: skipped.
TEST(HostileRender, GpuOutOfMemoryNamesTheResolution) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "no address-space limit under AddressSanitizer";
#endif
  const fs::path d = fs::temp_directory_path() / ("nimbus_surfaces_oom_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  const SplitResult r = run_nimbus_split({"render", "--preset", "steam", "--voxel-size", "0.05", "--scene", "none", "--res",
                                          "16384x16384", "--ms-method", "octaves", "--slices", "8", "-o",
                                          (d / "o.exr").string()});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("--res 16384x16384: the GPU ran out of memory"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(d / "o.exr"));
  fs::remove_all(d);
}

}  // namespace
}  // namespace nimbus::test
