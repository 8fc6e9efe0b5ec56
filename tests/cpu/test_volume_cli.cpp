// nimbus presets / generate / bench volume: what users type, what they get, and bad input.
#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include <filesystem>
#include <string>

#include "support/run_nimbus.hpp"

namespace {

using nimbus::test::run_nimbus;

std::filesystem::path temp_dir() {
  auto d = std::filesystem::temp_directory_path() / ("nimbus_vcli_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

TEST(VolumeCli, PresetsListsEveryGenusAndShowPrintsDocumentedParameters) {
  const auto r = run_nimbus("presets");
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* name : {"cumulus-humilis", "cumulus-mediocris", "cumulus-congestus", "cumulonimbus-capillatus-incus",
                           "stratocumulus-stratiformis-perlucidus", "altocumulus-lenticularis", "cirrus-fibratus",
                           "stratus", "steam", "smoke"})
    EXPECT_NE(r.output.find(name), std::string::npos) << name;
  const auto show = run_nimbus("presets show stratus");
  ASSERT_EQ(show.code, 0);
  EXPECT_NE(show.output.find("\"docs\""), std::string::npos);
  EXPECT_NE(show.output.find("\"coverage\""), std::string::npos);
  const auto bad = run_nimbus("presets show nimbostratus-imaginarius");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.output.find("nimbostratus-imaginarius"), std::string::npos);
}

TEST(VolumeCli, GenerateWritesAFogVolumeAndSequencesNamedByFrame) {
  const auto dir = temp_dir();
  const auto one = dir / "steam.vdb";
  auto r = run_nimbus("generate --preset steam --res 32 --set coverage=0.6 -o " + one.string());
  ASSERT_EQ(r.code, 0) << r.output;
  openvdb::initialize();
  openvdb::io::File f(one.string());
  f.open();
  const auto grids = f.readAllGridMetadata();
  f.close();
  bool density = false, temperature = false;
  for (const auto& g : *grids) {
    density |= g->getName() == "density" && g->getGridClass() == openvdb::GRID_FOG_VOLUME;
    temperature |= g->getName() == "temperature";
  }
  EXPECT_TRUE(density);
  EXPECT_TRUE(temperature);  // steam is a hot gas
  r = run_nimbus("generate --preset cumulus-humilis --res 24 --frames 7-8 --fps 12 -o " + (dir / "cu.vdb").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "cu.0007.vdb"));
  EXPECT_TRUE(std::filesystem::exists(dir / "cu.0008.vdb"));
  EXPECT_FALSE(std::filesystem::exists(dir / "cu.vdb"));
  std::filesystem::remove_all(dir);
}

TEST(VolumeCli, GenerateBadInputExitsTwoNamingTheInput) {
  const auto out = (temp_dir() / "x.vdb").string();
  struct Case {
    std::string args, mentions;
  } cases[] = {
      {"generate --preset cumulus-humilis --up x -o " + out, "--up"},
      {"generate --preset cumulus-humilis --res 0 -o " + out, "--res"},
      {"generate --preset cumulus-humilis --voxel-size -1 -o " + out, "--voxel-size"},
      {"generate --preset cumulus-humilis --voxel-size 5 --res 20 -o " + out, "--res"},
      {"generate --preset cumulus-humilis --frames 5-2 -o " + out, "--frames"},
      {"generate --preset cumulus-humilis --frames 1-2 --time 3 -o " + out, "--time"},
      {"generate --preset cumulus-humilis --set colour=3 -o " + out, "colour"},
      {"generate --preset cumulus-humilis --set coverage=2 -o " + out, "coverage"},
      {"generate --preset cumulus-humilis --params /nonexistent/p.json -o " + out, "p.json"},
      {"generate --preset cloud-of-unknowing -o " + out, "cloud-of-unknowing"},
      {"generate --preset cumulus-humilis", "--output"},
      {"generate --preset cumulus-humilis --size 0 --plan-json", "--size: must be within [0.01, 100], got 0"},
      {"generate --preset cumulus-humilis --size nan -o " + out, "--size"},
      {"generate --preset cumulus-humilis --plan-json -o " + out, "--plan-json: writes no file"},
      {"generate --preset cumulus-humilis --plan-json --brick 0/2", "--plan-json"},
      {"generate --preset cumulus-humilis --voxel-size 0.001 -o " + out, "GiB"},
  };
  for (const auto& c : cases) {
    const auto r = run_nimbus(c.args);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.mentions), std::string::npos) << c.args << "\n" << r.output;
  }
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(VolumeCli, BenchVolumeQuickRunsAndSparseMatchesTheAnchor) {
  const auto r = run_nimbus("bench volume --quick");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("naive, all octaves (anchor)"), std::string::npos);
  EXPECT_NE(r.output.find("0 (identical)"), std::string::npos);
  // Reading: sealed files in process, foreign copies by the reader program, values as OpenVDB
  // reads them; the reader's start is reported.
  EXPECT_NE(r.output.find("foreign, by the reader program ms"), std::string::npos);
  EXPECT_NE(r.output.find("The reader program's start"), std::string::npos);
  EXPECT_NE(r.output.find("0 / 0 (identical)"), std::string::npos);
  EXPECT_EQ(r.output.find("NOT"), std::string::npos);
  EXPECT_EQ(run_nimbus("bench volume --res 3").code, 2);
}

}  // namespace
