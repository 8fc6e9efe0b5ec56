// The half-angle slicer against closed forms: alpha of homogeneous boxes (one, and two one behind
// the other), the ambient term alone, the octave sum, the slicing axis it reports, no NaN or Inf
// at the hard cases, bad settings refused.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "nimbus/render/clouds/cloud_renderer.hpp"
#include "test_cloud_slices_support.hpp"
#include "test_gl_support.hpp"

namespace nimbus::render {
namespace {

using namespace slice_test;

constexpr int kN = 24;
constexpr double kVoxel = 1.0 / kN;

// Alpha of a homogeneous n^3 box (density 1, voxel h) seen along rays that stay inside its
// plateau (|x|, |y| <= (n-1)/2 h) across the whole support in z: the trilinear density ramps
// from 0 to 1 over the voxel beyond each face, so the optical depth is sigma n h / |dir.z|.
// Measured: |alpha error| <= 8.3e-4 (64 slices; thin box near the switch), tolerance 1e-3.
struct BoxCase {
  double sigma_per_m;
  glm::dvec3 to_light;
};

class HomogeneousBox : public ::testing::TestWithParam<BoxCase> {};

TEST_P(HomogeneousBox, AlphaIsClosedFormTransmittance) {
  NIMBUS_REQUIRE_GL();
  const BoxCase p = GetParam();
  CloudRenderer r({cube_cloud(kN, kVoxel, [](int, int, int) { return 1.0f; }, grey_optics(p.sigma_per_m))}, GL_R32F);
  const Camera cam = look_at_origin({0.0, 0.0, 3.0}, 64, 20.0);
  Light light;
  light.direction_to_sun = p.to_light;
  CloudSliceSettings s;
  s.slices = 64;
  s.light_res = 64;
  const Image img = r.render(cam, light, s);
  const double plateau = 0.5 * (kN - 1) * kVoxel, face = plateau + kVoxel;
  int checked = 0;
  double worst = 0.0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const glm::dvec3 d = pixel_ray(cam, x, y);
      bool inside = true;
      for (double z : {face, -face}) {
        const glm::dvec3 q = cam.eye + d * ((z - cam.eye.z) / d.z);
        inside = inside && std::abs(q.x) <= plateau && std::abs(q.y) <= plateau;
      }
      if (!inside) continue;
      const double expected = 1.0 - std::exp(-p.sigma_per_m * kN * kVoxel / std::abs(d.z));
      worst = std::max(worst, std::abs(img.pixel(x, y)[3] - expected));
      ++checked;
    }
  EXPECT_GT(checked, 1000);
  EXPECT_LT(worst, 1e-3) << "largest |alpha - closed form| over " << checked << " pixels";
}

INSTANTIATE_TEST_SUITE_P(CloudSlices, HomogeneousBox,
                         ::testing::Values(BoxCase{2.0, {0.3, 0.4, 1.0}},    // front-lit: under
                                           BoxCase{2.0, {0.3, 0.4, -1.0}},   // back-lit: over
                                           BoxCase{0.2, {1.0, 0.1, 0.05}},   // near the switch, thin
                                           BoxCase{20.0, {-0.2, 1.0, 0.3}})); // dense

TEST(CloudSlices, TwoBoxesOneBehindTheOtherMultiplyTransmittance) {
  NIMBUS_REQUIRE_GL();
  const int n = 12;
  std::vector<CloudVolume> clouds;
  clouds.push_back(cube_cloud(n, kVoxel, [](int, int, int) { return 1.0f; }, grey_optics(1.0), {0, 0, 0.5}, "front"));
  clouds.push_back(cube_cloud(n, kVoxel, [](int, int, int) { return 1.0f; }, grey_optics(3.0), {0, 0, -0.5}, "back"));
  CloudRenderer r(clouds, GL_R32F);
  const Camera cam = look_at_origin({0.0, 0.0, 4.0}, 48, 8.0);
  CloudSliceSettings s;
  s.slices = 96;
  s.light_res = 64;
  const Image img = r.render(cam, Light{}, s);
  const double plateau = 0.5 * (n - 1) * kVoxel, face = plateau + kVoxel;
  double worst = 0.0;
  int checked = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const glm::dvec3 d = pixel_ray(cam, x, y);
      bool inside = true;
      for (double z : {0.5 + face, 0.5 - face, -0.5 + face, -0.5 - face}) {
        const glm::dvec3 q = cam.eye + d * ((z - cam.eye.z) / d.z);
        inside = inside && std::abs(q.x) <= plateau && std::abs(q.y) <= plateau;
      }
      if (!inside) continue;
      const double expected = 1.0 - std::exp(-(1.0 + 3.0) * n * kVoxel / std::abs(d.z));
      worst = std::max(worst, std::abs(img.pixel(x, y)[3] - expected));
      ++checked;
    }
  EXPECT_GT(checked, 300);
  EXPECT_LT(worst, 1e-3) << "largest |alpha - closed form|";
}

// Ambient light alone: every slab's colour is albedo L alpha_i, so C = albedo L A exactly.
TEST(CloudSlices, AmbientAloneGivesAlbedoTimesRadianceTimesAlpha) {
  NIMBUS_REQUIRE_GL();
  CloudOptics o = grey_optics(6.0);
  o.albedo = {0.9, 0.8, 0.7};
  o.ambient_radiance = {0.5, 1.0, 2.0};
  CloudRenderer r({cube_cloud(kN, kVoxel, [](int i, int j, int k) { return lumpy_ball(i, j, k); }, o)}, GL_R32F);
  Light light;
  light.irradiance_w_m2 = glm::dvec3(0.0);
  CloudSliceSettings s;
  s.slices = 48;
  s.light_res = 64;
  for (glm::dvec3 eye : {glm::dvec3(0.4, 0.5, 2.5), glm::dvec3(-0.3, 0.2, -2.5)}) {
    const Image img = r.render(look_at_origin(eye, 48), light, s);
    int covered = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const float* p = img.pixel(x, y);
        covered += p[3] > 0.05f;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(p[c], o.albedo[c] * o.ambient_radiance[c] * p[3], 1e-5) << x << "," << y;
      }
    EXPECT_GT(covered, 200);
  }
  // Switched off, the ambient term adds nothing.
  s.ambient = false;
  const Image dark = r.render(look_at_origin({0.4, 0.5, 2.5}, 48), light, s);
  for (std::size_t i = 0; i < dark.rgba.size(); ++i)
    if (i % 4 != 3) {
      ASSERT_EQ(dark.rgba[i], 0.0f);
    }
}

// One extra octave with occlusion, contribution and eccentricity 1 repeats the single-scattering
// term exactly: the radiance doubles, alpha stays.
TEST(CloudSlices, IdenticalOctaveDoublesTheRadiance) {
  NIMBUS_REQUIRE_GL();
  CloudOptics o = grey_optics(8.0);
  o.phase = Phase{PhaseKind::HenyeyGreenstein, 0.5};
  CloudRenderer r({cube_cloud(kN, kVoxel, [](int i, int j, int k) { return lumpy_ball(i, j, k); }, o)}, GL_R32F);
  const Camera cam = look_at_origin({0.3, 0.6, 2.5}, 48);
  CloudSliceSettings s;
  s.slices = 48;
  s.light_res = 64;
  const Image one = r.render(cam, Light{}, s);
  s.multiple.octaves = 1;
  s.multiple.occlusion = s.multiple.contribution = s.multiple.eccentricity = 1.0;
  const Image two = r.render(cam, Light{}, s);
  double sum = 0.0;
  for (std::size_t i = 0; i < one.rgba.size(); ++i) {
    const double expected = i % 4 == 3 ? one.rgba[i] : 2.0 * one.rgba[i];
    EXPECT_NEAR(two.rgba[i], expected, 1e-5 * (1.0 + expected));
    sum += one.rgba[i];
  }
  EXPECT_GT(sum, 1.0);
}

// Kniss's forward-scattering blur spreads the light buffer with weights that sum to 1: where the
// light field is uniform across the light (inside a box lit along its axis, away from its sides)
// it changes nothing, near the sides it does, and a vanishing cone gives the unblurred image.
TEST(CloudSlices, BlurConservesAUniformLightField) {
  NIMBUS_REQUIRE_GL();
  CloudRenderer r({cube_cloud(kN, kVoxel, [](int, int, int) { return 1.0f; }, grey_optics(3.0))}, GL_R32F);
  const Camera cam = look_at_origin({0.0, 0.0, 3.0}, 48, 24.0);
  Light light;
  light.direction_to_sun = {0.0, 0.0, 1.0};  // along the box's z axis, from the camera's side
  CloudSliceSettings s;
  s.slices = 64;
  s.light_res = 128;
  const Image sharp = r.render(cam, light, s);
  s.blur_cone_rad = 0.3;
  const Image blurred = r.render(cam, light, s);
  s.blur_cone_rad = 1e-9;
  const Image vanishing = r.render(cam, light, s);
  double inner = 0.0, outer = 0.0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const glm::dvec3 d = pixel_ray(cam, x, y);
      const glm::dvec3 q = cam.eye + d * (3.5 / -d.z);  // beyond the box
      const bool interior = std::abs(q.x) < 0.35 && std::abs(q.y) < 0.35;
      for (int c = 0; c < 3; ++c) {
        const double v = sharp.pixel(x, y)[c];
        const double change = std::abs(blurred.pixel(x, y)[c] - v) / (v + 1e-3);
        (interior ? inner : outer) = std::max(interior ? inner : outer, change);
        EXPECT_NEAR(vanishing.pixel(x, y)[c], v, 1e-6 * (1.0 + v));
      }
    }
  EXPECT_LT(inner, 1e-4) << "relative change inside";  // the spread is ~0.02 m, 6 sigma from the sides
  EXPECT_GT(outer, 3e-3) << "relative change near the sides";  // measured 6e-3
}

TEST(CloudSlices, ReportsTheSlicingAxisAndOrder) {
  NIMBUS_REQUIRE_GL();
  CloudRenderer r({cube_cloud(kN, kVoxel, [](int i, int j, int k) { return lumpy_ball(i, j, k); }, grey_optics(4.0))});
  const Camera cam = look_at_origin({0.0, 0.0, 3.0}, 32);
  CloudSliceSettings s;
  s.slices = 40;
  s.light_res = 32;
  CloudFrameStats st;
  Light light;
  light.direction_to_sun = {0.0, 0.0, 1.0};  // behind the camera: propagation along the view
  Image img = r.render(cam, light, s, nullptr, &st);
  EXPECT_TRUE(st.front_to_back);
  EXPECT_NEAR(st.half_angle_rad, 0.0, 1e-9);
  EXPECT_GT(st.slices_drawn, 30);
  EXPECT_LE(st.slices_drawn, 40);
  EXPECT_GE(st.total_ms, st.slices_ms);
  EXPECT_FALSE(st.timing.empty());
  EXPECT_EQ(img.metadata.at("method"), "cloud-slices");
  EXPECT_NE(img.metadata.at("slices").find("40 slices"), std::string::npos);
  light.direction_to_sun = {1.0, 0.0, 0.0};  // exactly 90 degrees: the switch, 45 degrees each
  r.render(cam, light, s, nullptr, &st);
  EXPECT_TRUE(st.front_to_back);
  EXPECT_NEAR(st.half_angle_rad, M_PI / 4, 1e-9);
  light.direction_to_sun = {0.0, 0.6, -0.8};  // behind the cloud
  r.render(cam, light, s, nullptr, &st);
  EXPECT_FALSE(st.front_to_back);
  s.branch = CloudSliceSettings::Branch::FrontToBack;
  r.render(cam, light, s, nullptr, &st);
  EXPECT_TRUE(st.front_to_back);
}

struct HardCase {
  std::string name;
  glm::dvec3 eye, to_light;
  double sigma_per_m;
  bool empty;  // density 0 everywhere in the box
  CloudSliceSettings::Branch branch;
  double blur_cone_rad;
  int octaves;
};

class HardCases : public ::testing::TestWithParam<HardCase> {};

TEST_P(HardCases, NoNanOrInf) {
  NIMBUS_REQUIRE_GL();
  const HardCase& p = GetParam();
  CloudOptics o = grey_optics(p.sigma_per_m);
  o.phase = dual_lobe_phase(0.8, -0.3, 0.7);
  o.ambient_radiance = glm::dvec3(0.3);
  const auto density = [&](int i, int j, int k) { return p.empty ? 0.0f : lumpy_ball(i, j, k); };
  CloudRenderer r({cube_cloud(kN, kVoxel, density, o)});
  Light light;
  light.direction_to_sun = p.to_light;
  CloudSliceSettings s;
  s.slices = 24;
  s.light_res = 32;
  s.branch = p.branch;
  s.blur_cone_rad = p.blur_cone_rad;
  s.multiple.octaves = p.octaves;
  Image img;
  ASSERT_NO_THROW(img = r.render(look_at_origin(p.eye, 32), light, s)) << p.name;
  EXPECT_TRUE(all_finite(img)) << p.name;
  for (std::size_t i = 0; i < img.rgba.size(); ++i) {
    EXPECT_GE(img.rgba[i], 0.0f) << p.name;
    if (i % 4 == 3) {
      EXPECT_LE(img.rgba[i], 1.0f) << p.name;
    }
  }
}

using B = CloudSliceSettings::Branch;
const glm::dvec3 kFront(0.0, 0.0, 3.0);
INSTANTIATE_TEST_SUITE_P(
    CloudSlices, HardCases,
    ::testing::Values(HardCase{"parallel", kFront, {0, 0, 1}, 5.0, false, B::Auto, 0.0, 0},
                      HardCase{"antiparallel", kFront, {0, 0, -1}, 5.0, false, B::Auto, 0.0, 0},
                      HardCase{"ninety", kFront, {1, 0, 0}, 5.0, false, B::Auto, 0.0, 0},
                      HardCase{"forced_under_antiparallel", kFront, {0, 0, -1}, 5.0, false, B::FrontToBack, 0.0, 0},
                      HardCase{"forced_over_parallel", kFront, {0, 0, 1}, 5.0, false, B::BackToFront, 0.0, 0},
                      HardCase{"camera_inside", {0.05, 0.02, 0.1}, {0.3, 0.8, -0.5}, 5.0, false, B::Auto, 0.0, 0},
                      HardCase{"extinction_huge", kFront, {0.3, 0.8, 0.5}, 1e4, false, B::Auto, 0.0, 3},
                      HardCase{"extinction_tiny", kFront, {0.3, 0.8, -0.5}, 1e-9, false, B::Auto, 0.0, 3},
                      HardCase{"density_zero", kFront, {0.3, 0.8, 0.5}, 5.0, true, B::Auto, 0.0, 0},
                      HardCase{"blur_wide", kFront, {0.3, 0.8, -0.5}, 1e4, false, B::Auto, 1.5, 2},
                      HardCase{"blur_grazing", kFront, {1, 0, 0}, 5.0, false, B::BackToFront, 0.3, 0}),
    [](const ::testing::TestParamInfo<HardCase>& param) { return param.param.name; });

TEST(CloudSlices, BadSettingsAreRejected) {
  auto refused = [](CloudSliceSettings s, const std::string& field) {
    try {
      validate(s);
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
      return;
    }
    ADD_FAILURE() << "accepted a bad " << field;
  };
  CloudSliceSettings s;
  EXPECT_NO_THROW(validate(s));
  for (int v : {1, 4097}) {
    CloudSliceSettings b;
    b.slices = v;
    refused(b, "slices");
  }
  for (int v : {15, 4097}) {
    CloudSliceSettings b;
    b.light_res = v;
    refused(b, "light_res");
  }
  for (double v : {-0.1, std::nan(""), M_PI / 2, std::numeric_limits<double>::infinity()}) {
    CloudSliceSettings b;
    b.blur_cone_rad = v;
    refused(b, "blur_cone_rad");
  }
  CloudSliceSettings b;
  b.multiple.octaves = 4;
  refused(b, "octaves");
  b = CloudSliceSettings{};
  b.multiple.occlusion = 0.0;
  refused(b, "occlusion");
  b = CloudSliceSettings{};
  b.branch = static_cast<CloudSliceSettings::Branch>(7);
  refused(b, "branch");
}

TEST(CloudSlices, BadRendererInputsAreRejected) {
  NIMBUS_REQUIRE_GL();
  EXPECT_THROW(CloudRenderer(std::vector<CloudVolume>{}), std::invalid_argument);
  CloudVolume bad = cube_cloud(4, 0.1, [](int, int, int) { return 1.0f; }, grey_optics(1.0), {}, "broken");
  bad.optics.extinction_per_m = -1.0;
  try {
    CloudRenderer r({bad});
    ADD_FAILURE() << "accepted a negative extinction";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("broken"), std::string::npos) << e.what();
  }
  CloudRenderer r({cube_cloud(4, 0.1, [](int, int, int) { return 1.0f; }, grey_optics(1.0))});
  CloudSliceSettings s;
  s.slices = 0;
  EXPECT_THROW(r.render(look_at_origin({0, 0, 2}, 16), Light{}, s), std::invalid_argument);
  SceneUnderlay u;  // no textures
  EXPECT_THROW(r.render(look_at_origin({0, 0, 2}, 16), Light{}, CloudSliceSettings{}, &u), std::invalid_argument);
}

}  // namespace
}  // namespace nimbus::render
