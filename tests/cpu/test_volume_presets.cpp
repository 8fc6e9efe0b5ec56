// Presets: every shipped file maps onto CloudParams, documents every key, and takes
// --set / --params overrides; mistakes name the key.
#include <gtest/gtest.h>

#include <algorithm>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "nimbus/volume/preset.hpp"

namespace nimbus::volume {
namespace {

TEST(VolumePresets, EveryPresetParsesRoundTripsAndDocumentsEveryKey) {
  const auto& presets = list_presets();
  ASSERT_FALSE(presets.empty());
  EXPECT_EQ(&presets, &list_presets()) << "the list is parsed once and kept, not parsed per call";
  EXPECT_TRUE(std::is_sorted(presets.begin(), presets.end(),
                             [](const PresetInfo& a, const PresetInfo& b) { return a.name < b.name; }));
  for (const auto& info : presets) {
    const nlohmann::json doc = load_preset(info.name);
    EXPECT_EQ(doc.at("name"), info.name) << "file name and \"name\" differ";
    EXPECT_FALSE(info.genus.empty()) << info.name;
    EXPECT_GT(info.description.size(), 20u) << info.name;
    ASSERT_TRUE(doc.at("voxel_size").is_number()) << info.name;
    EXPECT_GT(doc.at("voxel_size").get<double>(), 0.0);
    const CloudParams p = cloud_from_json(doc.at("cloud"), info.name + ".cloud");
    // JSON -> params -> JSON -> params is the identity.
    const CloudParams q = cloud_from_json(cloud_to_json(p), "round trip");
    EXPECT_EQ(cloud_to_json(p), cloud_to_json(q)) << info.name;
    for (const auto& [key, value] : doc.at("cloud").items())
      EXPECT_TRUE(doc.at("docs").contains(key)) << info.name << ": key '" << key << "' is not documented";
  }
}

TEST(VolumePresets, SetOverridesExistingKeysAndRejectsUnknownOnes) {
  nlohmann::json doc = load_preset(list_presets().front().name);
  nlohmann::json& cloud = doc["cloud"];
  set_key(cloud, "coverage=0.7");
  set_key(cloud, "wind=[1, 2, 3]");
  set_key(cloud, "shapes.0.size=[100, 200, 50]");
  set_key(cloud, "noise=wavelet");
  const CloudParams p = cloud_from_json(cloud, "cloud");
  EXPECT_DOUBLE_EQ(p.coverage, 0.7);
  EXPECT_EQ(p.wind, glm::dvec3(1, 2, 3));
  EXPECT_EQ(p.shapes[0].size, glm::dvec3(100, 200, 50));
  EXPECT_EQ(p.noise, noise::Kind::Wavelet);
  for (const char* bad : {"colour=3", "shapes.99.size=[1,1,1]", "coverage", "=3", "gas.exponent=2"}) {
    nlohmann::json c = cloud;
    EXPECT_THROW(set_key(c, bad), std::invalid_argument) << bad;
  }
  // A wrong value is caught when the parameters are read, naming the key.
  nlohmann::json c = cloud;
  set_key(c, "coverage=1.5");
  try {
    cloud_from_json(c, "cloud");
    ADD_FAILURE() << "coverage 1.5 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("coverage"), std::string::npos) << e.what();
  }
  c = cloud;
  set_key(c, "octaves=\"many\"");
  EXPECT_THROW(cloud_from_json(c, "cloud"), std::invalid_argument);
}

TEST(VolumePresets, ParamsFileMergesAndBadFilesNameTheFile) {
  const auto dir = std::filesystem::temp_directory_path() / ("nimbus_presets_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto good = dir / "p.json", broken = dir / "broken.json";
  std::ofstream(good) << R"({"coverage": 0.33, "wind": [0, 4, 0]})";
  std::ofstream(broken) << "{ not json";
  nlohmann::json doc = load_preset(list_presets().front().name);
  merge_params_file(doc, good.string());
  const CloudParams p = cloud_from_json(doc.at("cloud"), "cloud");
  EXPECT_DOUBLE_EQ(p.coverage, 0.33);
  EXPECT_EQ(p.wind, glm::dvec3(0, 4, 0));
  for (const auto& path : {broken, dir / "missing.json"}) {
    try {
      merge_params_file(doc, path.string());
      ADD_FAILURE() << path;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(path.filename().string()), std::string::npos) << e.what();
    }
  }
  std::filesystem::remove_all(dir);
}

TEST(VolumePresets, UnknownPresetListsTheKnownOnes) {
  try {
    load_preset("cumulonimbus-mammatus-supercell");
    ADD_FAILURE();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(list_presets().front().name), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace nimbus::volume
