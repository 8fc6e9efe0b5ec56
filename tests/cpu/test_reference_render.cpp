// Whole reference images: every preset renders finite, non-negative pixels with metadata and
// progress; a mirror-symmetric scene gives a mirror-symmetric image; the lit-interval search
// has converged (more shadow-ray samples change nothing); bad input names the field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "nimbus/render/reference/reference_renderer.hpp"

namespace nr = nimbus::render;

namespace {

nr::Camera tiny(nr::Camera c, int w = 32, int h = 18) {
  c.width = w;
  c.height = h;
  return c;
}

void expect_error_naming(const nr::Scene& s, const nr::Camera& c, const nr::ReferenceSettings& st,
                         const std::string& field) {
  try {
    nr::render_reference(s, c, st);
    FAIL() << "no error for a bad " << field;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(ReferenceRender, EveryPresetIsFiniteWithMetadataAndProgress) {
  for (const std::string& name : nr::scene_names()) {
    const nr::Scene s = nr::make_scene(name);
    std::vector<double> reported;
    nr::ReferenceSettings settings;
    settings.progress = [&](double f) { reported.push_back(f); };
    const nr::Image img = nr::render_reference(s, tiny(s.camera), settings);
    ASSERT_EQ(img.width, 32);
    ASSERT_EQ(img.height, 18);
    double brightest = 0.0;
    for (std::size_t i = 0; i < img.rgba.size(); ++i) {
      ASSERT_TRUE(std::isfinite(img.rgba[i])) << name;
      ASSERT_GE(img.rgba[i], 0.0f) << name;
      if (i % 4 == 3) {
        EXPECT_EQ(img.rgba[i], 1.0f) << name << ": fog everywhere, so every pixel is opaque";
      } else {
        brightest = std::max(brightest, double(img.rgba[i]));
      }
    }
    EXPECT_GT(brightest, 0.0) << name;
    EXPECT_EQ(img.metadata.at("method"), "reference");
    EXPECT_EQ(img.metadata.at("scene"), name);
    EXPECT_FALSE(img.metadata.at("camera").empty());
    EXPECT_EQ(img.metadata.at("visibility_samples"), "1024");
    EXPECT_FALSE(img.metadata.at("medium").empty());
    EXPECT_FALSE(img.metadata.at("lights").empty());
    ASSERT_EQ(reported.size(), 18u) << name;
    EXPECT_TRUE(std::is_sorted(reported.begin(), reported.end()));
    EXPECT_DOUBLE_EQ(reported.back(), 1.0);
  }
}

TEST(ReferenceRender, MirrorSymmetricSceneGivesAMirrorSymmetricImage) {
  // Colonnade-like pillars symmetric about x = 0, a light on the plane x = 0, camera on it.
  nr::Scene s;
  s.name = "mirror";
  s.medium.extinction_per_m = 0.06;
  s.medium.phase = nr::Phase{nr::PhaseKind::HenyeyGreenstein, 0.3};
  s.ground = nr::GroundPlane{0.0, {{0.5, 0.5, 0.5}}};
  for (const double x : {-3.0, -1.0, 1.0, 3.0}) s.boxes.push_back({{x - 0.3, 0, -0.3}, {x + 0.3, 4, 0.3}, {}});
  s.spheres.push_back({{-1.5, 2.0, 3.0}, 0.4, {}});
  s.spheres.push_back({{1.5, 2.0, 3.0}, 0.4, {}});
  s.lamps.push_back(nr::bulb_light({0.0, 2.0, -2.0}, glm::dvec3{50.0}, 0.05));
  s.camera.eye = {0.0, 1.5, 9.0};
  s.camera.look_at = {0.0, 2.0, 0.0};
  const nr::Camera c = tiny(s.camera, 24, 14);
  nr::ReferenceSettings settings;
  settings.rel_tol = 1e-7;
  const nr::Image img = nr::render_reference(s, c, settings);
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width / 2; ++x) {
      const float a = img.pixel(x, y)[0], b = img.pixel(c.width - 1 - x, y)[0];
      EXPECT_NEAR(a, b, 1e-5f * std::max(a, b)) << x << "," << y;
    }
  }
}

TEST(ReferenceRender, LitIntervalSearchHasConverged) {
  // Eight times as many shadow-ray samples along each ray find no further visibility change.
  for (const std::string name : {"colonnade", "lamps", "colonnade-sun", "terrain"}) {
    const nr::Scene s = nr::make_scene(name);
    const nr::Camera c = tiny(s.camera, 20, 12);
    nr::ReferenceSettings coarse, fine;
    coarse.visibility_samples = 256;
    fine.visibility_samples = 2048;
    const nr::Image a = nr::render_reference(s, c, coarse), b = nr::render_reference(s, c, fine);
    for (std::size_t i = 0; i < a.rgba.size(); ++i) {
      EXPECT_NEAR(a.rgba[i], b.rgba[i], 1e-3f * b.rgba[i] + 1e-9f) << name << " value " << i;
    }
  }
}

TEST(ReferenceRender, BadInputNamesTheField) {
  const nr::Scene good = nr::make_scene("spheres");
  const nr::Camera cam = tiny(good.camera);
  nr::Scene s = good;
  s.spheres[0].radius_m = -0.5;
  expect_error_naming(s, cam, {}, "spheres[0].radius_m");
  s = good;
  s.medium.extinction_per_m = std::nan("");
  expect_error_naming(s, cam, {}, "medium");
  nr::Camera c = cam;
  c.width = 0;
  expect_error_naming(good, c, {}, "width");
  c = cam;
  c.fov_deg = 180.0;
  expect_error_naming(good, c, {}, "fov_deg");
  nr::ReferenceSettings st;
  st.rel_tol = 0.0;
  expect_error_naming(good, cam, st, "rel_tol");
  st = {};
  st.threads = -1;
  expect_error_naming(good, cam, st, "threads");
  st = {};
  st.visibility_samples = 2;
  expect_error_naming(good, cam, st, "visibility_samples");
}
