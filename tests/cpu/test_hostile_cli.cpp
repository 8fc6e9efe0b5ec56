// Hostile input to the nimbus command line: each case is a table row of arguments,
// stdin and the expected refusal. Every run must exit with the expected code, print exactly one
// line on stderr that holds the expected words, print nothing on stdout, and leave the case's
// directory exactly as it was (no output written, replaced or half-written, no temporaries).
// Every refusal comes before any rendering, so the whole table runs in seconds.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "support/hostile_table.hpp"
#include "support/vdb_fixtures.hpp"

namespace nimbus::test {
namespace {

namespace fs = std::filesystem;

using Case = HostileCase;

class HostileCli : public ::testing::Test {
 protected:
  // Inputs for every case, made once (none by the program under test).
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() / ("nimbus_hostile_" + std::to_string(::getpid())));
    const fs::path& d = *dir_;
    fs::remove_all(d);
    fs::create_directories(d / "sub");
    write_bytes(d / "p.json", R"({"coverage": 0.5})");
    write_bytes(d / "big.json", "{\"x\": \"" + std::string(17u << 20, 'a') + "\"}");  // over 16 MiB
    write_bytes(d / "deep.json", std::string(100000, '[') + std::string(100000, ']'));
    write_bytes(d / "null_cloud.json", R"({"cloud": null})");
    write_bytes(d / "null_coverage.json", R"({"coverage": null})");
    write_bytes(d / "abc_coverage.json", R"({"coverage": "abc"})");
    write_bytes(d / "abc_voxel.json", R"({"voxel_size": "abc", "cloud": {}})");
    write_bytes(d / "key_break.json", R"({"a\nb": 1})");  // a key holding a line break
    write_bytes(d / "script.json", R"({"frames": 1})");
    write_bytes(d / "file", "a regular file, not a directory");
    write_bytes(d / "long_field.csv", "1,1,1,1," + std::string(100, 'x') + "\n");
    std::string rows;
    for (int i = 0; i <= 1000000; ++i) rows += "1,1,1,1,1\n";
    write_bytes(d / "many_rows.csv", rows);
    ::mkfifo((d / "fifo").c_str(), 0600);
    fs::create_symlink("/dev/null", d / "null.vdb");
    openvdb::io::File file((d / "cloud.vdb").string());
    file.write({make_ball(6, 0.1)});
    file.close();
    fs::copy_file(d / "cloud.vdb", d / "cloud.exr");  // a VDB named as an image: an input -o may name
    // Periodic files (the "period_m" metadata generate writes for a field's tile) whose period is
    // shorter than the cloud (1.3 m across), or no period at all.
    for (const auto& [name, period] : {std::pair<std::string, std::string>{"short", "0.3 0.3"}, {"nan", "nan 1"},
                                       {"huge", "1e300 1"}, {"negative", "-1 1"}}) {
      openvdb::MetaMap meta;
      meta.insertMeta("period_m", openvdb::StringMetadata(period));
      openvdb::io::File periodic((d / ("period_" + name + ".vdb")).string());
      periodic.write({make_ball(6, 0.1)}, meta);
      periodic.close();
    }
    // A cloud of one voxel (0.1 m) repeated every nanometre: 1024 copies in each voxel, drawn for 25 s.
    openvdb::MetaMap meta;
    meta.insertMeta("period_m", openvdb::StringMetadata("1e-9 1e-9"));
    const openvdb::FloatGrid::Ptr voxel = openvdb::FloatGrid::create(0.0f);
    voxel->setName("density");
    voxel->setTransform(openvdb::math::Transform::createLinearTransform(0.1));
    voxel->getAccessor().setValueOn(openvdb::Coord(0, 0, 0), 1.0f);
    openvdb::io::File tiny((d / "period_tiny.vdb").string());
    tiny.write({voxel}, meta);
    tiny.close();
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }

  static void expect_refused(const std::vector<Case>& cases) { test::expect_refused(*dir_, cases); }

  static fs::path* dir_;
};
fs::path* HostileCli::dir_ = nullptr;

const std::vector<std::string> kGenerate = {"generate", "--preset", "steam", "--voxel-size", "0.02"};
const std::vector<std::string> kCumulus = {"generate", "--preset", "cumulus-humilis", "--voxel-size", "100"};
const std::vector<std::string> kTinyScene = {"render", "--scene", "lamps", "--method", "analytic", "--res", "16x16"};
const std::vector<std::string> kTinyClouds = {"render", "--preset", "steam", "--voxel-size", "0.05",
                                              "--scene",  "none",   "--res",  "8x8"};

std::vector<std::string> with(std::vector<std::string> head, const std::vector<std::string>& tail) {
  head.insert(head.end(), tail.begin(), tail.end());
  return head;
}

TEST_F(HostileCli, InputFilesHaveSizeDepthAndKindLimits) {
  expect_refused({
      {with(kGenerate, {"--params", "{d}/big.json", "-o", "{d}/o.vdb"}), 2, "larger than the limit of 16 MiB"},
      {with(kGenerate, {"--params", "{d}/deep.json", "-o", "{d}/o.vdb"}), 2, "nested deeper than 64 levels"},
      {with(kGenerate, {"--set", "coverage=" + std::string(100000, '['), "-o", "{d}/o.vdb"}), 2,
       "nested deeper than 64 levels"},
      {with(kGenerate, {"--params", "{d}/sub", "-o", "{d}/o.vdb"}), 2, "--params {d}/sub: is a directory"},
      {with(kGenerate, {"--params", "{d}/fifo", "-o", "{d}/o.vdb"}), 2, "--params {d}/fifo: is a FIFO"},
      {with(kGenerate, {"--params", "/dev/zero", "-o", "{d}/o.vdb"}), 2, "is a character device"},
      {{"render", "--view-state", "{d}/deep.json", "-o", "{d}/v.exr"}, 1, "nested deeper than 64 levels"},
      {{"render", "--view-state", "{d}/big.json", "-o", "{d}/v.exr"}, 1, "larger than the limit of 16 MiB"},
      {{"render", "--view-state", "{d}/fifo", "-o", "{d}/v.exr"}, 1, "is a FIFO"},
      {{"view", "--headless", "--script", "{d}/deep.json"}, 1, "nested deeper than 64 levels"},
      {{"info", "{d}/fifo"}, 1, "FILE '{d}/fifo': is a FIFO"},
      {{"info", "{d}/sub"}, 1, "FILE '{d}/sub': is a directory"},
      {{"render", "{d}/fifo", "--scene", "none", "--res", "8x8", "-o", "{d}/c.exr"}, 1, "FILE '{d}/fifo': is a FIFO"},
      {{"compare", "/dev/zero", "{d}/cloud.exr"}, 1, "TEST '/dev/zero': is a character device"},
  });
}

TEST_F(HostileCli, StdinHasLineRowAndEchoLimits) {
  expect_refused({
      {{"airlight"}, 2, "stdin line 1: longer than 4096 bytes", "/dev/zero"},
      {{"airlight"}, 2, "stdin: more than 1000000 rows", "{d}/many_rows.csv"},
      {{"airlight"}, 2, "'" + std::string(40, 'x') + "...' is not a number", "{d}/long_field.csv"},
  });
}

TEST_F(HostileCli, EveryFlagMustApplyToWhatWasAsked) {
  const std::string clouds_only = "applies to clouds (FILE.vdb or --preset), not to a scene alone";
  expect_refused({
      {with(kTinyScene, {"--sun", "nan,1,1", "-o", "{d}/s.exr"}), 2, "--sun: " + clouds_only},
      {with(kTinyScene, {"--slices", "64", "-o", "{d}/s.exr"}), 2, "--slices: " + clouds_only},
      {with(kTinyScene, {"--multiple", "2", "-o", "{d}/s.exr"}), 2, "--multiple: " + clouds_only},
      {with(kTinyScene, {"--frames", "1-2", "--fps", "0", "-o", "{d}/s.exr"}), 2, clouds_only},
      {with(kTinyScene, {"--cloud-extinction", "5", "-o", "{d}/s.exr"}), 2, "--cloud-extinction: " + clouds_only},
      {with(kTinyClouds, {"--hide-bulbs", "-o", "{d}/c.exr"}), 2, "--hide-bulbs: applies to a scene alone, not to clouds"},
      {with(kTinyClouds, {"--jitter", "none", "-o", "{d}/c.exr"}), 2, "--jitter: applies to a scene alone"},
      {with(kTinyClouds, {"--shadow-res", "64", "-o", "{d}/c.exr"}), 2, "--shadow-res: applies to a scene alone"},
      {with(kTinyClouds, {"--extinction", "0.1", "-o", "{d}/c.exr"}), 2, "--extinction: applies to a scene alone"},
      {with(kTinyClouds, {"--albedo", "0.5", "-o", "{d}/c.exr"}), 2, "--albedo: applies to a scene alone"},
      {with(kTinyClouds, {"--phase", "rayleigh", "-o", "{d}/c.exr"}), 2, "--phase: applies to a scene alone"},
      {{"render", "--view-state", "{d}/p.json", "--slices", "8", "-o", "{d}/v.exr"}, 2,
       "--slices: applies to clouds (FILE.vdb or --preset), not to a view state"},
  });
}

TEST_F(HostileCli, EmptyValuesAreRefused) {
  expect_refused({
      {with(kTinyScene, {"--eye", "", "-o", "{d}/s.exr"}), 2, "--eye: the value is empty"},
      {{"render", "--scene", "lamps", "--res", "", "-o", "{d}/s.exr"}, 2, "--res: the value is empty"},
      {with(kTinyScene, {"--preview", "", "-o", "{d}/s.exr"}), 2, "--preview: the value is empty"},
      {{"noise", "--res", "4", "--simd", "", "-o", "{d}/n.vdb"}, 2, "--simd: the value is empty"},
      {with(kGenerate, {"--set", "", "-o", "{d}/o.vdb"}), 2, "--set: the value is empty"},
      {{"info", ""}, 2, "file: the value is empty"},
      {{"info", "{d}/cloud.vdb", "--grid", ""}, 2, "--grid: the value is empty"},
  });
}

TEST_F(HostileCli, JsonNullsAndWrongTypesNameTheKey) {
  expect_refused({
      {with(kGenerate, {"--params", "{d}/null_cloud.json", "-o", "{d}/o.vdb"}), 2, "cloud: null is not a value"},
      {with(kGenerate, {"--params", "{d}/null_coverage.json", "-o", "{d}/o.vdb"}), 2, "coverage: null is not a value"},
      {with(kGenerate, {"--params", "{d}/abc_coverage.json", "-o", "{d}/o.vdb"}), 2,
       "coverage: expected a number, got \"abc\""},
      {with(kGenerate, {"--params", "{d}/abc_voxel.json", "-o", "{d}/o.vdb"}), 2, "voxel_size: expected a number"},
      {with(kGenerate, {"--set", "coverage=null", "-o", "{d}/o.vdb"}), 2, "--set coverage: null is not a value"},
      {with(kGenerate, {"--params", "{d}/key_break.json", "-o", "{d}/o.vdb"}), 2, "steam.a?b: unknown key"},
      {with(kGenerate, {"--set", "shapes.99999999999999999999=1", "-o", "{d}/o.vdb"}), 2,
       "--set shapes.99999999999999999999: unknown key '99999999999999999999'"},
      {with(kGenerate, {"--set", "coverage=[1]", "-o", "{d}/o.vdb"}), 2, "coverage: expected a number, got an array"},
      {with(kGenerate, {"--set", "shapes=[{}]", "-o", "{d}/o.vdb"}), 2, "shapes[0].kind: missing"},
      // A shape far smaller than a voxel gives an empty grid, which is no result to write.
      {with(kGenerate, {"--set", R"(shapes=[{"kind": "ellipsoid", "center": [0, 0, 0], "size": [1e-4, 1e-4, 1e-4]}])",
                        "-o", "{d}/o.vdb"}),
       1, "the cloud has no voxel"},
  });
}

TEST_F(HostileCli, RangesAreSaneBeforeAnyWork) {
  expect_refused({
      {with(kGenerate, {"--frames", "1-1000000", "-o", "{d}/o.vdb"}), 2, "add --many-frames"},
      {with(kTinyClouds, {"--frames", "1-20000", "-o", "{d}/c.exr"}), 2, "add --many-frames"},
      {{"render", "{d}/cloud.vdb", "--scene", "none", "--res", "8x8", "--frames", "1-2", "-o", "{d}/c.exr"}, 2,
       "--frames: every frame would render the same FILE"},
      {{"render", "{d}/cloud.vdb", "--grid", "nope", "--scene", "none", "--res", "8x8", "-o", "{d}/c.exr"}, 2,
       "--grid"},
      {{"info", "{d}/cloud.vdb", "--grid", "nope"}, 2, "--grid"},
      // Times have one range, for flags, files, view states and Python: 31 years either way.
      {with(kCumulus, {"--time", "1e12", "-o", "{d}/o.vdb"}), 2, "--time: t = 1e+12 s is outside [-1e+09, 1e+09] s of sky time"},
      {with(kTinyClouds, {"--time", "1e300", "-o", "{d}/c.exr"}), 2, "--time: t = 1e+300 s is outside [-1e+09, 1e+09] s"},
      // A file holds one moment: its picture was the same at any --time, to the byte.
      {{"render", "{d}/cloud.vdb", "--scene", "none", "--res", "8x8", "--time", "1e300", "-o", "{d}/c.exr"}, 2,
       "--time: t = 1e+300 s is outside"},
      {{"render", "{d}/cloud.vdb", "--scene", "none", "--res", "8x8", "--time", "5", "-o", "{d}/c.exr"}, 2,
       "--time: FILE clouds are the same at any time"},
  });
}

// Periods (a periodic field's "period_m") and the distance its copies are drawn to: hostile values
// of either are refused naming the file and key (exit 1: the file is at fault) or the flag (2).
TEST_F(HostileCli, PeriodsAndRepeatsAreRefusedNamingTheirSource) {
  const std::vector<std::string> file = {"render", "--scene", "none", "--res", "8x8", "-o", "{d}/c.exr"};
  expect_refused({
      // A period shorter than its cloud exited 2, a usage error, for a file's content.
      {with(file, {"{d}/period_short.vdb"}), 1,
       "{d}/period_short.vdb: metadata 'period_m': the period along x (0.3 m) is shorter than the cloud"},
      {with(file, {"{d}/period_tiny.vdb", "--repeat-to", "1e6"}), 1,
       "{d}/period_tiny.vdb: metadata 'period_m': the period along x (1e-09 m) is shorter than a voxel (0.1 m)"},
      {with(file, {"{d}/period_nan.vdb"}), 1, "{d}/period_nan.vdb: metadata 'period_m' must be two periods in [0, 1e7] metres"},
      {with(file, {"{d}/period_huge.vdb"}), 1, "{d}/period_huge.vdb: metadata 'period_m' must be two periods"},
      {with(file, {"{d}/period_negative.vdb"}), 1, "{d}/period_negative.vdb: metadata 'period_m' must be two periods"},
      {with(kTinyClouds, {"--repeat-to", "nan", "-o", "{d}/c.exr"}), 2, "--repeat-to: must be in [0, 1e+06] metres, got nan"},
      {with(kTinyClouds, {"--repeat-to", "-1", "-o", "{d}/c.exr"}), 2, "--repeat-to: must be in [0, 1e+06] metres, got -1"},
      {with(kTinyClouds, {"--repeat-to", "1e300", "-o", "{d}/c.exr"}), 2, "--repeat-to: must be in [0, 1e+06] metres, got 1e+300"},
      {with(kTinyClouds, {"--repeat-to", "", "-o", "{d}/c.exr"}), 2, "--repeat-to: the value is empty"},
      // The path tracer and the reference draw each cloud once: --repeat-to was ignored.
      {with(kTinyClouds, {"--method", "pathtrace", "--repeat-to", "5000", "-o", "{d}/c.exr"}), 2,
       "--repeat-to: --method pathtrace draws each cloud once (the path tracer does not repeat a periodic field)"},
      {with(kTinyClouds, {"--method", "reference", "--repeat-to", "0", "-o", "{d}/c.exr"}), 2,
       "--repeat-to: --method reference draws each cloud once"},
  });
}

TEST_F(HostileCli, OutputsAreCheckedBeforeTheWork) {
  expect_refused({
      {with(kGenerate, {"--params", "{d}/p.json", "-o", "{d}/p.json"}), 2, "-o '{d}/p.json': is also --params"},
      {with(kGenerate, {"--params", "{d}/p.json", "-o", "{d}/sub/../p.json"}), 2, "is also --params '{d}/p.json'"},
      {{"render", "{d}/cloud.exr", "--scene", "none", "--res", "8x8", "-o", "{d}/cloud.exr"}, 2, "is also FILE"},
      {{"view", "--headless", "--script", "{d}/script.json", "--state-out", "{d}/script.json"}, 2,
       "--state-out '{d}/script.json': is also --script"},
      {{"noise", "--res", "4", "-o", "{d}/fifo"}, 1, "-o '{d}/fifo': is a FIFO; only a regular file is replaced"},
      {{"noise", "--res", "4", "-o", "{d}/null.vdb"}, 1, "is a symbolic link; only a regular file is replaced"},
      {{"noise", "--res", "4", "-o", "{d}/sub"}, 1, "-o '{d}/sub': is a directory"},
      {with(kGenerate, {"-o", "{d}/file/o.vdb"}), 1, "-o '{d}/file/o.vdb': {d}/file is not a directory"},
      // A scene render whose preview cannot be written: refused before rendering, so no EXR is
      // left behind (it used to be written, and then the preview failed).
      {with(kTinyScene, {"-o", "{d}/s.exr", "--preview", "{d}/file/s.png"}), 1, "--preview '{d}/file/s.png'"},
      {with(kTinyClouds, {"-o", "{d}/c.exr", "--preview", "{d}/file/c.png"}), 1, "--preview '{d}/file/c.png'"},
  });
}

// Values whose floats overflow on the GPU became NaN pixels reported by an internal stage ("cloud
// slices: pixel (6, 2) channel R is NaN"), or, for the sun, a light volume that never finished:
// now each flag is refused up front, naming itself.
TEST_F(HostileCli, ExtremeValuesAreRefusedBeforeTheyBecomeNaN) {
  expect_refused({
      {with(kTinyClouds, {"--cloud-extinction", "1e300", "-o", "{d}/c.exr"}), 2, "--cloud-extinction: must be in [0, 1e+12] per metre"},
      {with(kTinyClouds, {"--ambient", "1e300,1,1", "-o", "{d}/c.exr"}), 2, "--ambient: '1e300,1,1' must be three numbers within +-1e12"},
      {with(kTinyClouds, {"--lamp", "0,0,0.1", "--lamp-intensity", "1e38", "-o", "{d}/c.exr"}), 2,
       "--lamp-intensity: '1e38' must be within +-1e12"},
      {with(kTinyClouds, {"--sun", "1e300,1,1", "-o", "{d}/c.exr"}), 2, "--sun: '1e300,1,1' must be three numbers within +-1e12"},
      {with(kTinyClouds, {"--eye", "1e300,0,0", "-o", "{d}/c.exr"}), 2, "--eye: '1e300,0,0' must be three numbers within +-1e12"},
      {{"render", "--scene", "lamps", "--method", "raymarch:8", "--res", "16x16", "--extinction", "1e300", "-o", "{d}/s.exr"}, 2,
       "--extinction: must be at most 1e12"},
      {with(kTinyScene, {"--exposure", "1e300", "--preview", "{d}/s.png", "-o", "{d}/s.exr"}), 2,
       "--exposure: must be in [-64, 64] stops"},
      // A lamp's bulb in a scene at 1e12 W/sr: 1.3e14 W/(m^2 sr), clipped to the EXR's 65504.
      {{"render", "--preset", "steam", "--voxel-size", "0.05", "--res", "8x8", "--lamp", "0,-0.3,0.15", "--lamp-intensity",
        "1e12", "--ms-method", "octaves", "-o", "{d}/c.exr"},
       2, "--lamp-intensity: 1e+12 W/sr makes each --lamp's bulb, seen in the scene, 1.27324e+14 W/(m^2 sr), beyond the 65504"},
      // A direction too short to survive normalising in floats named the internal field
      // ("light direction_to_sun must be finite and non-zero"), not the flag.
      {with(kTinyClouds, {"--sun", "1e-30,0,1e-30", "-o", "{d}/c.exr"}), 2,
       "--sun: '1e-30,0,1e-30' is too short a direction (length 1.41421e-30, below 1e-12)"},
      // The sun's bearing has the range of sky files and view states, [0, 360]; it took any number.
      {with(kTinyClouds, {"--sun-elevation", "30", "--sun-azimuth", "1e300", "-o", "{d}/c.exr"}), 2,
       "--sun-azimuth: must be in [0, 360] degrees, got 1e+300"},
      {with(kTinyClouds, {"--sun-elevation", "30", "--sun-azimuth", "-1", "-o", "{d}/c.exr"}), 2,
       "--sun-azimuth: must be in [0, 360] degrees, got -1"},
      // A voxel of 1e300 m: a brick of one empty voxel was written, exit 0.
      {{"generate", "--preset", "steam", "--voxel-size", "1e300", "--brick", "0/1", "-o", "{d}/b.vdb"}, 2, "--voxel-size: must be"},
      {{"render", "--preset", "steam", "--voxel-size", "1e300", "--scene", "none", "--res", "8x8", "-o", "{d}/c.exr"}, 2,
       "--voxel-size: must be"},
  });
}

TEST_F(HostileCli, FloatOverflowIsRefusedNotDropped) {
  expect_refused({
      // cumulus-humilis has exponent 1.3: (1e30 x its peak)^1.3 is beyond a float; such voxels
      // were written as 0, a hollow cloud.
      {with(kCumulus, {"--set", "density=1e30", "--float", "-o", "{d}/o.vdb"}), 2, "density 1e+30 with exponent 1.3"},
      {with(kCumulus, {"--set", "density=1e38", "--float", "-o", "{d}/o.vdb"}), 2, "beyond the float range"},
  });
}

}  // namespace
}  // namespace nimbus::test
