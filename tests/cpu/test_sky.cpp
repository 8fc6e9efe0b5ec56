// Sky files (volume/sky.hpp): the shipped default, round trips, errors that name the key, and
// each cloud's model parameters.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

#include <glm/glm.hpp>

#include "nimbus/volume/preset.hpp"
#include "nimbus/volume/sky.hpp"

namespace nimbus::volume {
namespace {

using json = nlohmann::json;

json minimal() {
  return json::parse(R"({"clouds": [{"preset": "cumulus-humilis", "position": [100, -200, 50], "seed": 9}],
                         "wind": [5, -2, 0], "evolution": 2.5, "sun": {"elevation": 20, "azimuth": 300},
                         "voxel_size": 40, "keyframe_interval": 12})");
}

std::string error_of(const json& doc) {
  try {
    sky_from_json(doc, "sky");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Sky, DefaultSkyHasSeveralCloudsOfDifferentKindsAndSomethingHigher) {
  const Sky s = default_sky();
  std::set<std::string> presets, seeds;
  double highest_base = 0.0;
  size_t clouds = 0;  // a field entry holds many
  for (std::size_t i = 0; i < s.clouds.size(); ++i) {
    const CloudParams p = sky_cloud_params(s, i);
    clouds += p.field ? field_layout(*p.field).size() : 1;
    presets.insert(s.clouds[i].preset);
    seeds.insert(s.clouds[i].preset + "/" + std::to_string(s.clouds[i].seed));
    highest_base = std::max(highest_base, sky_cloud_params(s, i).base_altitude + s.clouds[i].position_m.z);
  }
  EXPECT_GE(clouds, 100u) << "a sky of many clouds";
  EXPECT_GE(presets.size(), 3u) << "clouds of different sizes";
  EXPECT_EQ(seeds.size(), s.clouds.size()) << "no two clouds of one preset share a seed";
  EXPECT_GT(highest_base, 4000.0) << "something higher than the cumulus";
  EXPECT_GT(glm::length(s.wind_m_s), 0.0);
}

TEST(Sky, JsonRoundTripKeepsEveryField) {
  const Sky a = sky_from_json(minimal(), "sky");
  EXPECT_EQ(a.clouds[0].position_m, glm::dvec3(100, -200, 50));
  EXPECT_EQ(a.clouds[0].seed, 9u);
  EXPECT_EQ(a.wind_m_s, glm::dvec3(5, -2, 0));
  EXPECT_EQ(a.evolution_scale, 2.5);
  EXPECT_EQ(a.sun_elevation_deg, 20.0);
  EXPECT_EQ(a.sun_azimuth_deg, 300.0);
  EXPECT_EQ(a.voxel_size_m, 40.0);
  EXPECT_EQ(a.keyframe_interval_s, 12.0);
  const Sky b = sky_from_json(sky_to_json(a), "sky");
  EXPECT_EQ(sky_to_json(a), sky_to_json(b));
}

TEST(Sky, FileRoundTripIsAtomicAndErrorsNameTheFile) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("nimbus_test_sky_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const Sky a = sky_from_json(minimal(), "sky");
  save_sky_file(a, (dir / "a.json").string());
  EXPECT_EQ(sky_to_json(load_sky_file((dir / "a.json").string())), sky_to_json(a));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1)
      << "no temporary file left";
  try {
    load_sky_file((dir / "missing.json").string());
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.json"), std::string::npos);
  }
  std::ofstream(dir / "bad.json") << "{ not json";
  EXPECT_THROW(load_sky_file((dir / "bad.json").string()), std::runtime_error);
  std::filesystem::remove_all(dir);
}

TEST(Sky, BadContentsNameTheKey) {
  json j = minimal();
  j["colour"] = 1;
  EXPECT_NE(error_of(j).find("sky.colour: unknown key"), std::string::npos) << error_of(j);
  j = minimal();
  j["clouds"][0]["preset"] = "cumulus-nonexistent";
  EXPECT_NE(error_of(j).find("cumulus-nonexistent"), std::string::npos);
  j = minimal();
  j["clouds"][0]["overrides"] = {{"no_such_key", 1}};
  EXPECT_NE(error_of(j).find("overrides.no_such_key"), std::string::npos) << error_of(j);
  j = minimal();
  j["clouds"][0]["overrides"] = {{"coverage", 7}};
  EXPECT_NE(error_of(j).find("coverage"), std::string::npos) << error_of(j);
  j = minimal();
  j["wind"] = {1e9, 0, 0};
  EXPECT_NE(error_of(j).find("sky.wind[0]"), std::string::npos) << error_of(j);
  j = minimal();
  j["clouds"] = json::array();
  EXPECT_NE(error_of(j).find("sky.clouds"), std::string::npos);
  j = minimal();
  j["sun"] = {{"elevation", 95}};
  EXPECT_NE(error_of(j).find("sun.elevation"), std::string::npos);
  j = minimal();
  j["voxel_size"] = 0.1;
  EXPECT_NE(error_of(j).find("voxel_size"), std::string::npos);
  j = minimal();
  j.erase("clouds");
  EXPECT_NE(error_of(j).find("clouds is missing"), std::string::npos);
  j = minimal();
  j["clouds"][0]["seed"] = 1.5;
  EXPECT_NE(error_of(j).find("seed"), std::string::npos);
}

TEST(Sky, CloudParamsTakeSeedOverridesAndScaledEvolutionWithoutWind) {
  json j = minimal();
  j["clouds"][0]["overrides"] = {{"coverage", 0.41}, {"wind", {9, 9, 9}}};
  const Sky s = sky_from_json(j, "sky");
  const CloudParams p = sky_cloud_params(s, 0);
  const CloudParams preset = cloud_from_json(load_preset("cumulus-humilis").at("cloud"), "preset");
  EXPECT_EQ(p.seed, 9u);
  EXPECT_DOUBLE_EQ(p.coverage, 0.41);
  EXPECT_EQ(p.wind, glm::dvec3(0.0)) << "the drift is a translation at render time";
  EXPECT_DOUBLE_EQ(p.evolution, 2.5 * preset.evolution);
  EXPECT_EQ(p.shapes.size(), preset.shapes.size());
}

}  // namespace
}  // namespace nimbus::volume
