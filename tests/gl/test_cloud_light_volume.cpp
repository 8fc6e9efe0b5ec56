// The slicer's light-volume method (shaders/lib/cloud_light_volume.glsl): with a volume of zeros
// it is single scattering to the bit; with a hand-made volume (fluence growing along x, a flux
// toward the eye) it adds eq. MS-1 along every ray as a CPU march of the same model does; and the
// frame pipeline builds the volume once, again only when the sun's direction changes.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "nimbus/render/clouds/cloud_renderer.hpp"
#include "nimbus/render/core/light_volume.hpp"
#include "nimbus/render/frame/frame_renderer.hpp"
#include "test_cloud_slices_support.hpp"
#include "test_gl_support.hpp"

namespace nimbus::render {
namespace {

using namespace slice_test;

constexpr int kN = 24;
constexpr double kVoxel = 1.0 / kN;

CloudVolume ball(const Phase& phase) {
  CloudOptics o = grey_optics(6.0, 0.9);
  o.phase = phase;
  return cube_cloud(kN, kVoxel, [](int i, int j, int k) { return lumpy_ball(i, j, k); }, o);
}

// 8^3 cells over [-0.6, 0.6]^3: fluence (2 + 3 (x + 0.6)) (1, 0.8, 0.6) per unit irradiance,
// flux (0, 0, 0.5) x the mean fluence (toward +z, the eye), second moment diag(-0.1, -0.05, 0.15)
// + 0.05 (xy, xz, yz) off the diagonal, times the mean.
LightVolume made_volume(bool zero) {
  LightVolume v;
  v.size[0] = v.size[1] = v.size[2] = 8;
  v.world_min = glm::dvec3(-0.6);
  v.cell_m = glm::dvec3(0.15);
  v.fluence_rgb.assign(v.cells() * 3, 0.0f);
  v.flux_xyz.assign(v.cells() * 3, 0.0f);
  v.quadrupole.assign(v.cells() * 5, 0.0f);
  if (zero) return v;
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) {
        const std::size_t q = static_cast<std::size_t>(i + 8 * (j + 8 * k));
        const double x = -0.6 + (i + 0.5) * v.cell_m.x;
        const double phi = 2.0 + 3.0 * (x + 0.6);
        v.fluence_rgb[3 * q] = static_cast<float>(phi);
        v.fluence_rgb[3 * q + 1] = static_cast<float>(0.8 * phi);
        v.fluence_rgb[3 * q + 2] = static_cast<float>(0.6 * phi);
        v.flux_xyz[3 * q + 2] = static_cast<float>(0.5 * 0.8 * phi);
        const float quad[5] = {-0.1f, -0.05f, 0.05f, 0.05f, 0.05f};
        for (int e = 0; e < 5; ++e) v.quadrupole[5 * q + e] = static_cast<float>(quad[e] * 0.8 * phi);
      }
  return v;
}

CloudSliceSettings settings(bool light_volume) {
  CloudSliceSettings s;
  s.slices = 96;
  s.light_res = 64;
  s.jitter = false;
  if (light_volume) s.multiple.method = MultipleScatteringMethod::LightVolume;
  return s;
}

Light side_sun() {
  Light l;
  l.direction_to_sun = glm::dvec3(0.6, 0.7, 0.3);
  l.irradiance_w_m2 = glm::dvec3(2.0);
  return l;
}

TEST(CloudLightVolume, ZeroVolumeIsSingleScatteringToTheBit) {
  NIMBUS_REQUIRE_GL();
  CloudRenderer r({ball(dual_lobe_phase(0.7, -0.25, 0.8))}, GL_R32F);
  const Camera cam = look_at_origin({0.4, 0.3, 3.0}, 48, 30.0);
  const Image single = r.render(cam, side_sun(), settings(false));
  EXPECT_THROW(r.render(cam, side_sun(), settings(true)), std::logic_error);  // no volume yet
  r.set_light_volume(made_volume(true));
  const Image with = r.render(cam, side_sun(), settings(true));
  ASSERT_EQ(single.rgba.size(), with.rgba.size());
  double covered = 0.0;
  for (std::size_t i = 0; i < single.rgba.size(); ++i) {
    EXPECT_EQ(single.rgba[i], with.rgba[i]) << "value " << i;
    if (i % 4 == 3) covered += single.rgba[i];
  }
  EXPECT_GT(covered, 50.0);  // the ball is in view
}

// made_volume with eq. MS-4's fit varying from cell to cell (a checkerboard of +-0.3 in h about
// a gradient (0.2, 0.1, 0) per cell) and the lobes of orders 1 and 2 (f 0.2 and 0.1 about mu 0.8
// and 0.5): what the eye pass reads within a cell and toward the sun.
LightVolume fitted_volume() {
  LightVolume v = made_volume(false);
  v.gradient.assign(v.cells() * 4, 0.0f);
  v.lobes.assign(v.cells() * 4, 0.0f);
  v.light_direction = -glm::normalize(side_sun().direction_to_sun);
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) {
        const std::size_t q = static_cast<std::size_t>(i + 8 * (j + 8 * k));
        v.gradient[4 * q] = 0.2f;
        v.gradient[4 * q + 1] = 0.1f;
        v.gradient[4 * q + 3] = static_cast<float>(0.2 * (i + 0.5) + 0.1 * (j + 0.5) + ((i + j + k) % 2 ? 0.3 : -0.3));
        const float lobes[4] = {0.2f, 0.8f, 0.1f, 0.5f};
        for (int e = 0; e < 4; ++e) v.lobes[4 * q + e] = lobes[e];
      }
  return v;
}

// The slicer's added light (light volume minus single scattering) against a CPU march of eq.
// MS-1 with the same volume, over the pixels the cloud covers: relative RMS and the worst pixel
// over the peak.
// With `per_sample`, a second cloud of another phase (the same ball, with an extinction that adds
// nothing measurable) makes the eye pass read the volume at every sample (MS_VOLUME 1) instead of
// the frame's radiance toward the eye, which is made for one phase (MS_VOLUME 2).
std::pair<double, double> eq_ms1_error(const LightVolume& v, const Phase& phase, const glm::dvec3& eye,
                                       bool per_sample = false) {
  const CloudVolume cloud = ball(phase);
  std::vector<CloudVolume> clouds{cloud};
  if (per_sample) {
    CloudVolume ghost = ball(dual_lobe_phase(-0.3, 0.0, 1.0));
    ghost.optics.extinction_per_m = 1e-9;
    clouds.push_back(ghost);
  }
  CloudRenderer r(clouds, GL_R32F);
  const Camera cam = look_at_origin(eye, 48, 28.0);
  const Light sun = side_sun();
  const Image single = r.render(cam, sun, settings(false));
  r.set_light_volume(v);
  const Image with = r.render(cam, sun, settings(true));
  // The CPU: int albedo E M(x, -d) sigma_t rho T dt along each pixel's ray, in fine steps.
  double err2 = 0.0, ref2 = 0.0, worst = 0.0, peak = 0.0;
  int covered = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const glm::dvec3 d = pixel_ray(cam, x, y);
      const double t0 = glm::length(cam.eye) - 0.8, t1 = glm::length(cam.eye) + 0.8, dt = 0.0025;
      double T = 1.0;
      glm::dvec3 added(0.0);
      for (double t = t0 + 0.5 * dt; t < t1; t += dt) {
        const glm::dvec3 p = cam.eye + t * d;
        const double od = cloud.optics.extinction_per_m * sample_density(cloud, p) * dt;
        if (od <= 0.0) continue;
        const double alpha = 1.0 - std::exp(-od);
        added += cloud.optics.albedo * sun.irradiance_w_m2 * light_volume_inscatter(v, phase, p, -d) * (T * alpha);
        T *= 1.0 - alpha;
      }
      if (1.0 - T < 0.05) continue;
      ++covered;
      const float* a = with.pixel(x, y);
      const float* b = single.pixel(x, y);
      for (int c = 0; c < 3; ++c) {
        const double got = a[c] - b[c];
        err2 += (got - added[c]) * (got - added[c]);
        ref2 += added[c] * added[c];
        worst = std::max(worst, std::abs(got - added[c]));
        peak = std::max(peak, added[c]);
      }
    }
  EXPECT_GT(covered, 200);
  const double rel_rms = std::sqrt(err2 / ref2);
  std::printf("covered %d pixels: relative RMS %.4f, worst %.4f of a peak %.4f\n", covered, rel_rms, worst, peak);
  return {rel_rms, worst / peak};
}

// The eye pass interpolates the angular part made at the cell centres toward the eye
// (light_volume_radiance.comp.glsl); the CPU evaluates it at every step. Measured on llvmpipe:
// relative RMS 5e-4, worst 1.0e-3 of the peak (per sample, MS_VOLUME 1: 2e-4 and 1.0e-3);
// tolerance 0.5 % and 1 %.
TEST(CloudLightVolume, AddsEqMS1AlongEachRayAsTheCpuMarch) {
  NIMBUS_REQUIRE_GL();
  for (const bool per_sample : {false, true}) {
    const auto [rms, worst] = eq_ms1_error(made_volume(false), dual_lobe_phase(0.5, 0.0, 1.0), {0.0, 0.0, 3.0}, per_sample);
    EXPECT_LT(rms, 0.005) << (per_sample ? "per sample" : "the frame's radiance");
    EXPECT_LT(worst, 0.01) << (per_sample ? "per sample" : "the frame's radiance");
  }
}

// The same with eq. MS-4's fit changing from cell to cell and the lobes, from an eye closer in
// (the direction to it turns by up to 5 degrees across a cell), with a dual-lobe phase. Measured
// on llvmpipe: relative RMS 6e-4, worst 1.3e-3 of the peak (per sample: 1e-4 and 6e-4);
// tolerance 1 % and 2 %.
TEST(CloudLightVolume, AddsTheFitAndTheLobesAsTheCpuMarch) {
  NIMBUS_REQUIRE_GL();
  for (const bool per_sample : {false, true}) {
    const auto [rms, worst] = eq_ms1_error(fitted_volume(), dual_lobe_phase(0.7, -0.25, 0.8), {0.9, 0.6, 1.6}, per_sample);
    EXPECT_LT(rms, 0.01) << (per_sample ? "per sample" : "the frame's radiance");
    EXPECT_LT(worst, 0.02) << (per_sample ? "per sample" : "the frame's radiance");
  }
}

TEST(CloudLightVolume, FrameRendererBuildsOnceAndAgainOnlyForANewSunDirection) {
  NIMBUS_REQUIRE_GL();
  FrameSettings fs;
  fs.slices = settings(true);
  fs.slices.multiple.light_volume.resolution = 12;
  fs.slices.multiple.light_volume.photons = 4096;
  FrameRenderer frame(std::nullopt, side_sun(), fs);
  frame.set_clouds({ball(dual_lobe_phase(0.7, -0.25, 0.8))});
  const Camera cam = look_at_origin({0.4, 0.3, 3.0}, 32, 30.0);
  FrameStats st;
  const Image first = frame.render(cam, &st);
  EXPECT_TRUE(st.light_volume_rebuilt);
  EXPECT_NE(first.metadata.at("light_volume").find("4096 photons"), std::string::npos);
  frame.render(cam, &st);
  EXPECT_FALSE(st.light_volume_rebuilt);
  Light brighter = side_sun();
  brighter.irradiance_w_m2 = glm::dvec3(4.0);  // per unit irradiance: no rebuild
  frame.set_light(brighter);
  const Image twice = frame.render(cam, &st);
  EXPECT_FALSE(st.light_volume_rebuilt);
  for (std::size_t i = 0; i < first.rgba.size(); i += 4) EXPECT_NEAR(twice.rgba[i], 2.0f * first.rgba[i], 1e-5f + 1e-5f * first.rgba[i]);
  Light moved = brighter;
  moved.direction_to_sun = glm::dvec3(-0.6, 0.7, 0.3);
  frame.set_light(moved);
  frame.render(cam, &st);
  EXPECT_TRUE(st.light_volume_rebuilt);
  // Scattered light only adds: every pixel at least as bright as single scattering.
  FrameSettings off = fs;
  off.slices.multiple.method = MultipleScatteringMethod::Octaves;
  FrameRenderer single(std::nullopt, side_sun(), off);
  single.set_clouds({ball(dual_lobe_phase(0.7, -0.25, 0.8))});
  const Image ss = single.render(cam);
  double more = 0.0;
  for (std::size_t i = 0; i < ss.rgba.size(); i += 4) {
    EXPECT_GE(first.rgba[i], ss.rgba[i] - 1e-6f);
    more += first.rgba[i] - ss.rgba[i];
  }
  EXPECT_GT(more, 0.0);
}

}  // namespace
}  // namespace nimbus::render
