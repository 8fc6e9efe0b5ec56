// Scene presets (what each named scene is made of) and scene validation messages.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

#include "nimbus/render/scene/intersect.hpp"
#include "nimbus/render/scene/scene.hpp"

namespace nr = nimbus::render;

namespace {

void expect_error_naming(const nr::Scene& s, const std::string& field) {
  try {
    nr::validate(s);
    FAIL() << "no error for a bad " << field;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(ScenePresets, EveryNamedSceneIsValidWithA720pCamera) {
  const auto names = nr::scene_names();
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()),
            (std::set<std::string>{"lamps", "spots", "colonnade", "colonnade-sun", "spheres", "terrain", "open", "sky", "steam-lamp"}));
  for (const std::string& name : names) {
    const nr::Scene s = nr::make_scene(name);
    EXPECT_EQ(s.name, name);
    EXPECT_NO_THROW(nr::validate(s)) << name;
    EXPECT_EQ(s.camera.width, 1280) << name;
    EXPECT_EQ(s.camera.height, 720) << name;
    EXPECT_GT(s.medium.extinction_per_m, 0.0) << name;
    // The eye is in the open: no geometry within 0.5 m around it.
    const nr::SceneTracer tracer(s);
    for (const glm::dvec3 d : {glm::dvec3{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}) {
      EXPECT_FALSE(tracer.intersect(s.camera.eye, d, 0.5)) << name;
    }
  }
}

TEST(ScenePresets, UnknownNameListsTheKnownOnes) {
  try {
    nr::make_scene("lampz");
    FAIL();
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("lampz"), std::string::npos);
    for (const std::string& n : nr::scene_names()) EXPECT_NE(m.find(n), std::string::npos) << m;
  }
}

TEST(ScenePresets, LampsAreIdenticalAtDifferentDistances) {
  const nr::Scene s = nr::make_scene("lamps");
  ASSERT_EQ(s.lamps.size(), 3u);
  std::set<double> distances;
  for (const nr::Light& l : s.lamps) {
    EXPECT_EQ(l.intensity_w_sr, s.lamps[0].intensity_w_sr);
    EXPECT_NEAR(l.position_m.y, 5.0, 0.5);
    distances.insert(std::round(glm::length(l.position_m - s.camera.eye)));
  }
  EXPECT_EQ(distances.size(), 3u);
  EXPECT_TRUE(s.ground);
  EXPECT_EQ(s.medium.phase.kind, nr::PhaseKind::Isotropic);
  EXPECT_NEAR(s.medium.extinction_per_m, 0.04, 1e-12);
  // Each lamp is visible from the eye (the bulb is not hidden by its post or a house).
  const nr::SceneTracer tracer(s);
  for (const nr::Light& l : s.lamps) EXPECT_FALSE(tracer.occluded(s.camera.eye, l.position_m));
}

TEST(ScenePresets, ColonnadesShareTheirPillars) {
  const nr::Scene point = nr::make_scene("colonnade"), sun = nr::make_scene("colonnade-sun");
  EXPECT_EQ(point.medium.phase.kind, nr::PhaseKind::HenyeyGreenstein);
  EXPECT_NEAR(point.medium.phase.g, 0.3, 1e-12);
  ASSERT_EQ(point.lamps.size(), 1u);
  EXPECT_FALSE(point.sun);
  EXPECT_TRUE(sun.sun);
  EXPECT_TRUE(sun.lamps.empty());
  ASSERT_GE(point.boxes.size(), sun.boxes.size());
  for (std::size_t i = 0; i < sun.boxes.size(); ++i) EXPECT_EQ(point.boxes[i].min_m, sun.boxes[i].min_m);
  // Low sun behind the colonnade (away from the camera, which is at +z).
  const glm::dvec3 u = glm::normalize(sun.sun->direction_to_sun);
  EXPECT_GT(u.y, 0.0);
  EXPECT_LT(u.y, 0.5);
  EXPECT_LT(u.z, 0.0);
  EXPECT_GT(sun.camera.eye.z, 0.0);
  // Light leaves the hall between the pillars: from the light, the gap centres are lit at the
  // front and the pillar centres are dark behind them.
  const nr::SceneTracer tracer(point);
  const glm::dvec3 light = point.lamps[0].position_m;
  EXPECT_FALSE(tracer.occluded(light, {1.25, 3.0, 3.0}));
  EXPECT_TRUE(tracer.occluded(light, {0.0, 3.0, 3.0}));
}

TEST(ScenePresets, TerrainIsADeterministic65x65Heightfield) {
  const nr::Scene a = nr::make_scene("terrain"), b = nr::make_scene("terrain");
  ASSERT_TRUE(a.terrain);
  EXPECT_EQ(a.terrain->nx, 65);
  EXPECT_EQ(a.terrain->nz, 65);
  EXPECT_EQ(a.terrain->heights_m, b.terrain->heights_m);
  EXPECT_TRUE(a.sun);
  const auto ground = nr::heightfield_height(*a.terrain, a.camera.eye.x, a.camera.eye.z);
  ASSERT_TRUE(ground);
  EXPECT_GT(a.camera.eye.y - *ground, 3.0);
  ASSERT_TRUE(a.ground);  // closes the horizon beyond the heightfield, below all of it
  EXPECT_LT(a.ground->height_m, *std::min_element(a.terrain->heights_m.begin(), a.terrain->heights_m.end()));
}

TEST(ScenePresets, OpenSceneHasNothingToOcclude) {
  const nr::Scene s = nr::make_scene("open");
  EXPECT_FALSE(s.ground);
  EXPECT_FALSE(s.terrain);
  EXPECT_TRUE(s.boxes.empty());
  EXPECT_TRUE(s.spheres.empty());
  EXPECT_EQ(s.lamps.size(), 1u);
  EXPECT_FALSE(s.sun);
}

TEST(SceneValidation, ErrorsNameTheField) {
  const nr::Scene good = nr::make_scene("spheres");
  nr::Scene s = good;
  s.spheres[1].radius_m = -1.0;
  expect_error_naming(s, "spheres[1].radius_m");
  s = good;
  s.boxes.push_back({{0, 0, 0}, {1, -1, 1}, {}});
  expect_error_naming(s, "boxes[0].max_m");
  s = good;
  s.lamps.clear();
  expect_error_naming(s, "no light");
  s = good;
  s.lamps[0].intensity_w_sr.y = std::nan("");
  expect_error_naming(s, "lamps[0].intensity_w_sr");
  s = good;
  s.lamps[0].bulb_radius_m = -0.01;  // 0 is allowed: no visible bulb
  expect_error_naming(s, "lamps[0].bulb_radius_m");
  s = good;
  s.lamps[0].spot_axis = glm::dvec3(0.0, -1.0, 0.0);  // a spot among the lamps is welcome ...
  s.lamps[0].spot_inner_rad = 0.3;
  s.lamps[0].spot_outer_rad = 0.5;
  EXPECT_NO_THROW(nr::validate(s));
  s.lamps[0].spot_inner_rad = 0.7;  // ... its cone inside out is not
  expect_error_naming(s, "lamps[0].spot_inner_rad");
  s = good;
  s.lamps[0].position_m = s.spheres[2].centre_m;
  expect_error_naming(s, "lamps[0].position_m");
  s = good;
  s.ground->material.albedo = {0.5, 1.5, 0.5};
  expect_error_naming(s, "ground.material.albedo");
  s = good;
  s.camera.width = 0;
  expect_error_naming(s, "camera");
  s = good;
  s.camera.eye = s.spheres[0].centre_m;
  expect_error_naming(s, "camera.eye");
  s = good;
  s.camera.eye = s.lamps[0].position_m + glm::dvec3{0.01, 0.0, 0.0};
  expect_error_naming(s, "camera.eye");
  s = good;
  s.medium.extinction_per_m = -0.1;
  expect_error_naming(s, "medium");
  s = good;
  s.sun = nr::sun_light({0, 0, 0}, {1, 1, 1});
  expect_error_naming(s, "sun.direction_to_sun");

  nr::Scene t = nr::make_scene("terrain");
  t.terrain->heights_m.pop_back();
  expect_error_naming(t, "terrain.heights_m");
  t = nr::make_scene("terrain");
  t.terrain->nx = 1;
  expect_error_naming(t, "terrain.nx");
  t = nr::make_scene("terrain");
  t.terrain->spacing_m = 0.0;
  expect_error_naming(t, "terrain.spacing_m");
  t = nr::make_scene("terrain");
  t.terrain->heights_m[7] = INFINITY;
  expect_error_naming(t, "terrain.heights_m[7]");
}
