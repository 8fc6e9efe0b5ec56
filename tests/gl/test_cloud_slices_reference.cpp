// The half-angle slicer against the CPU reference of the same model (render_cloud_reference):
// relative RMSE over covered pixels front-lit and back-lit, isotropic and Henyey-Greenstein; a
// uniform sphere's dark side against its lit side; the two branches at their switch; no popping
// as the light crosses 90 degrees from the view.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "nimbus/render/reference/cloud_reference.hpp"
#include "nimbus/render/clouds/cloud_renderer.hpp"
#include "nimbus/render/image/image_metrics.hpp"
#include "test_cloud_slices_support.hpp"
#include "test_gl_support.hpp"

namespace nimbus::render {
namespace {

using namespace slice_test;

constexpr int kN = 24;
constexpr double kVoxel = 1.0 / kN;

struct RefCase {
  std::string name;
  glm::dvec3 to_light;
  double g;          // Henyey-Greenstein asymmetry, 0 = isotropic
  double tolerance;  // relative RMSE over covered pixels
};

// gtest prints a parameter with this (not as raw bytes) in its logs.
void PrintTo(const RefCase& c, std::ostream* os) { *os << c.name; }

// Measured (llvmpipe): rel RMSE 0.13-0.21 %; tolerance 1 %.
class AgainstReference : public ::testing::TestWithParam<RefCase> {};

TEST_P(AgainstReference, RelativeRmseWithinTolerance) {
  NIMBUS_REQUIRE_GL();
  const RefCase& p = GetParam();
  CloudOptics o = grey_optics(8.0, 0.9);
  o.phase = Phase{PhaseKind::HenyeyGreenstein, p.g};
  const std::vector<CloudVolume> clouds = {cube_cloud(kN, kVoxel, [](int i, int j, int k) { return lumpy_ball(i, j, k); }, o)};
  const Camera cam = look_at_origin({0.4, 0.3, 2.5}, 64, 30.0);
  Light light;
  light.direction_to_sun = p.to_light;
  const Image ref = render_cloud_reference(clouds, cam, light, quick_reference());
  CloudRenderer r(clouds, GL_R32F);
  CloudSliceSettings s;
  s.slices = 64;
  s.light_res = 128;
  const Image img = r.render(cam, light, s);
  const ImageError e = compare_images(img, ref);
  std::printf("[ slices vs reference ] %s: rel RMSE %.4f, bias %+.4f, median %.4f over %zu pixels\n", p.name.c_str(),
              e.rel_rmse, e.mean_bias, e.median_rel, e.pixels);
  EXPECT_GT(e.pixels, 1000u);
  EXPECT_LT(e.rel_rmse, p.tolerance) << p.name;
  double alpha_err = 0.0;
  for (std::size_t i = 3; i < img.rgba.size(); i += 4) alpha_err = std::max(alpha_err, std::abs(double(img.rgba[i]) - ref.rgba[i]));
  EXPECT_LT(alpha_err, 0.02) << p.name << ": largest |alpha - reference|";
}

INSTANTIATE_TEST_SUITE_P(CloudSlices, AgainstReference,
                         ::testing::Values(RefCase{"front_lit_isotropic", {0.5, 0.6, 0.8}, 0.0, 0.01},
                                           RefCase{"back_lit_isotropic", {-0.3, 0.5, -0.8}, 0.0, 0.01},
                                           RefCase{"front_lit_hg", {0.5, 0.6, 0.8}, 0.6, 0.01},
                                           RefCase{"back_lit_hg", {-0.3, 0.5, -0.8}, 0.6, 0.01}),
                         [](const ::testing::TestParamInfo<RefCase>& param) { return param.param.name; });

// A grid under a rotated, anisotropically scaled transform (oriented support, sheared bound):
// the slicer and the reference see the same density through their own world-to-index maps.
TEST(CloudSlices, OrientedGridMatchesReference) {
  NIMBUS_REQUIRE_GL();
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.0f);
  openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
  m.preScale(openvdb::Vec3d(1.0 / kN, 1.4 / kN, 0.7 / kN));
  m.postRotate(openvdb::math::X_AXIS, 0.4);
  m.postRotate(openvdb::math::Y_AXIS, 0.7);
  m.postTranslate(openvdb::Vec3d(-0.5, -0.6, -0.3));
  grid->setTransform(openvdb::math::Transform::createLinearTransform(m));
  auto acc = grid->getAccessor();
  for (int k = 0; k < kN; ++k)
    for (int j = 0; j < kN; ++j)
      for (int i = 0; i < kN; ++i) acc.setValue(openvdb::Coord(i, j, k), lumpy_ball(i, j, k));
  const std::vector<CloudVolume> clouds = {make_cloud_volume(*grid, grey_optics(8.0, 0.9), "oriented")};
  const Camera cam = look_at_origin({0.3, 0.5, 2.5}, 64, 40.0);
  Light light;
  light.direction_to_sun = {0.6, 0.5, -0.3};
  const Image ref = render_cloud_reference(clouds, cam, light, quick_reference());
  CloudRenderer r(clouds, GL_R32F);
  CloudSliceSettings s;
  s.slices = 64;
  s.light_res = 128;
  const ImageError e = compare_images(r.render(cam, light, s), ref);
  std::printf("[ oriented ] rel RMSE %.4f, bias %+.4f over %zu pixels\n", e.rel_rmse, e.mean_bias, e.pixels);
  EXPECT_GT(e.pixels, 500u);
  EXPECT_LT(e.rel_rmse, 0.01);  // measured 0.22 %
}

// The camera inside the cloud: the slab around the eye reaches back to the eye (no plane is
// drawn behind it). Measured rel RMSE 0.96 % and 0.55 %, bias -0.09 % and +0.07 %, where slabs
// cut at the near plane gave a 1.4 % bias that more slices did not reduce.
TEST(CloudSlices, CameraInsideMatchesReference) {
  NIMBUS_REQUIRE_GL();
  const std::vector<CloudVolume> clouds = {
      cube_cloud(kN, kVoxel, [](int i, int j, int k) { return lumpy_ball(i, j, k); }, grey_optics(4.0, 0.9))};
  CloudRenderer r(clouds, GL_R32F);
  Camera cam = look_at_origin({0.05, 0.1, 0.2}, 64, 60.0);
  cam.look_at = cam.eye + glm::dvec3(0.2, 0.1, -1.0);
  for (const glm::dvec3& to_light : {glm::dvec3(0.5, 0.6, 0.8), glm::dvec3(-0.3, 0.5, -0.8)}) {
    Light light;
    light.direction_to_sun = to_light;
    const Image ref = render_cloud_reference(clouds, cam, light, quick_reference());
    CloudSliceSettings s;
    s.slices = 64;
    s.light_res = 128;
    const ImageError e = compare_images(r.render(cam, light, s), ref);
    std::printf("[ inside ] rel RMSE %.4f, bias %+.4f\n", e.rel_rmse, e.mean_bias);
    EXPECT_GT(e.pixels, 3000u);
    EXPECT_LT(e.rel_rmse, 0.02);
    EXPECT_LT(std::abs(e.mean_bias), 0.005);
  }
}

// Mean radiance of the covered pixels whose ray passes left (side < 0) or right of the centre.
double side_mean(const Image& img, const Camera& cam, double side) {
  double sum = 0.0;
  int n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const double sx = glm::dot(pixel_ray(cam, x, y), camera_frame(cam).right);
      if (sx * side < 0.04 || img.pixel(x, y)[3] < 0.5) continue;
      sum += img.pixel(x, y)[1];
      ++n;
    }
  return n > 0 ? sum / n : 0.0;
}

// A uniform sphere lit from the side: the side facing away from the light is darker than the lit
// side by the factor the reference gives.
TEST(CloudSlices, UniformSphereDarkSideMatchesReference) {
  NIMBUS_REQUIRE_GL();
  const auto sphere = [](int i, int j, int k) {
    const double c = 0.5 * (kN - 1);
    const double r = std::sqrt((i - c) * (i - c) + (j - c) * (j - c) + (k - c) * (k - c)) * kVoxel;
    return r < 0.4 ? 1.0f : 0.0f;
  };
  const std::vector<CloudVolume> clouds = {cube_cloud(kN, kVoxel, sphere, grey_optics(6.0, 0.9))};
  const Camera cam = look_at_origin({0.0, 0.0, 2.5}, 64, 30.0);
  Light light;
  light.direction_to_sun = {1.0, 0.2, 0.3};  // from the right, a little from the camera's side
  const Image ref = render_cloud_reference(clouds, cam, light, quick_reference());
  CloudRenderer r(clouds, GL_R32F);
  CloudSliceSettings s;
  s.slices = 64;
  s.light_res = 128;
  const Image img = r.render(cam, light, s);
  const double ref_ratio = side_mean(ref, cam, -1.0) / side_mean(ref, cam, 1.0);
  const double ratio = side_mean(img, cam, -1.0) / side_mean(img, cam, 1.0);
  std::printf("[ sphere ] dark/lit: slices %.4f, reference %.4f\n", ratio, ref_ratio);
  EXPECT_LT(ref_ratio, 0.5);  // the setup has a dark side at all
  EXPECT_NEAR(ratio / ref_ratio, 1.0, 0.02);  // measured 0.3 %
}

// Light exactly 90 degrees from the view: both branches slice at 45 degrees to it, on opposite
// sides, and must give the same image (and the reference's).
TEST(CloudSlices, BranchesAgreeAtTheSwitch) {
  NIMBUS_REQUIRE_GL();
  CloudOptics o = grey_optics(8.0, 0.9);
  o.phase = Phase{PhaseKind::HenyeyGreenstein, 0.5};
  const std::vector<CloudVolume> clouds = {cube_cloud(kN, kVoxel, [](int i, int j, int k) { return lumpy_ball(i, j, k); }, o)};
  const Camera cam = look_at_origin({0.0, 0.4, 2.5}, 64, 30.0);
  const glm::dvec3 v = camera_frame(cam).forward;
  Light light;
  light.direction_to_sun = -rotate_towards(v, {1.0, 0.3, 0.0}, 90.0);
  CloudRenderer r(clouds, GL_R32F);
  CloudSliceSettings s;
  s.slices = 64;
  s.light_res = 128;
  s.branch = CloudSliceSettings::Branch::FrontToBack;
  const Image under = r.render(cam, light, s);
  s.branch = CloudSliceSettings::Branch::BackToFront;
  const Image over = r.render(cam, light, s);
  const Image ref = render_cloud_reference(clouds, cam, light, quick_reference());
  const double between = compare_images(under, over).rel_rmse;
  const double e_under = compare_images(under, ref).rel_rmse, e_over = compare_images(over, ref).rel_rmse;
  std::printf("[ switch ] under vs over %.4f; vs reference: under %.4f, over %.4f\n", between, e_under, e_over);
  // Measured 0.42 % between, 0.32 and 0.34 % against the reference.
  EXPECT_LT(between, 0.01);
  EXPECT_LT(e_under, 0.01);
  EXPECT_LT(e_over, 0.01);
}

// As the light sweeps through 90 degrees from the view (the branch switch) in 1-degree
// steps, the frame-to-frame change at the switch stays within twice the mean change between the
// other steps, with the jitter pattern fixed (the strict case: the two branches' noise differs)
// and varied from frame to frame. Measured at 48 slices (llvmpipe): 1.27x fixed, 1.03x varied;
// a fixed jitter pattern passes 2x down to about 34 slices (2.06x at 32, 3.1x at 24), the
// jitter-free image down to 24 (1.65x), a per-frame pattern at every count tried (<= 1.03x).
TEST(CloudSlices, NoPoppingAtTheSwitch) {
  NIMBUS_REQUIRE_GL();
  const std::vector<CloudVolume> clouds = {
      cube_cloud(kN, kVoxel, [](int i, int j, int k) { return lumpy_ball(i, j, k); }, grey_optics(8.0, 0.9))};
  const Camera cam = look_at_origin({0.0, 0.4, 2.5}, 64, 30.0);
  const glm::dvec3 v = camera_frame(cam).forward;
  CloudRenderer r(clouds, GL_R32F);
  CloudSliceSettings s;
  s.slices = 48;
  s.light_res = 128;
  for (bool vary_frame : {false, true}) {
    std::vector<Image> frames;
    for (int i = 0; i < 8; ++i) {  // 86.5 .. 93.5 degrees: the switch between frames 3 and 4
      Light light;
      light.direction_to_sun = -rotate_towards(v, {1.0, 0.3, 0.0}, 86.5 + i);
      s.frame = vary_frame ? static_cast<unsigned>(i) : 0u;
      frames.push_back(r.render(cam, light, s));
    }
    double others = 0.0, at_switch = 0.0;
    std::string trace;
    for (std::size_t i = 1; i < frames.size(); ++i) {
      const double change = rms_difference(frames[i], frames[i - 1]);
      trace += " " + std::to_string(change);
      if (i == 4) {
        at_switch = change;
      } else {
        others += change / static_cast<double>(frames.size() - 2);
      }
    }
    std::printf("[ popping ] jitter pattern %s: RMS change per 1-degree step%s\n", vary_frame ? "varied" : "fixed",
                trace.c_str());
    EXPECT_LE(at_switch, 2.0 * others) << trace;
  }
}

}  // namespace
}  // namespace nimbus::render
