// The CPU cloud reference against closed forms and independent integrals: alpha of boxes, single
// scattering of slabs, the ambient term, step convergence, shadow rays, bad settings.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "nimbus/render/reference/cloud_reference.hpp"
#include "nimbus/render/image/image_metrics.hpp"

namespace nr = nimbus::render;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A grid of nx x ny x nz voxels (indices from 0) holding `values` (x fastest), voxel edge
// `voxel_m`, voxel (i, j, k) centred at offset + voxel_m * (i, j, k).
nr::CloudVolume grid_cloud(int nx, int ny, int nz, const std::vector<float>& values, double voxel_m,
                           const glm::dvec3& offset, const nr::CloudOptics& optics) {
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel_m));
  grid->transform().postTranslate(openvdb::Vec3d(offset.x, offset.y, offset.z));
  auto acc = grid->getAccessor();
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) acc.setValue(openvdb::Coord(i, j, k), values[i + nx * (j + ny * k)]);
  return nr::make_cloud_volume(*grid, optics, "test");
}

nr::CloudVolume box_cloud(int nx, int ny, int nz, float rho, double voxel_m, const glm::dvec3& offset,
                          const nr::CloudOptics& optics) {
  return grid_cloud(nx, ny, nz, std::vector<float>(static_cast<std::size_t>(nx) * ny * nz, rho), voxel_m, offset,
                    optics);
}

std::vector<float> random_values(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<float> v(static_cast<std::size_t>(n));
  for (float& x : v) x = u(rng);
  return v;
}

nr::CloudOptics grey(double extinction_per_m, double albedo) {
  nr::CloudOptics o;
  o.extinction_per_m = extinction_per_m;
  o.albedo = glm::dvec3(albedo);
  return o;
}

// Henyey-Greenstein per steradian, written out here (not cloud_phase_value).
double hg(double g, double cos_theta) {
  return (1.0 - g * g) / (4.0 * kPi * std::pow(1.0 + g * g - 2.0 * g * cos_theta, 1.5));
}

// Exact optical depth of the piecewise-trilinear density along eye + t dir, t in [0, t_max]:
// the density is a cubic between the crossings of integer index planes, so 3-point
// Gauss-Legendre per piece is exact. Independent of sample_density: its own trilinear weights
// and its own world-to-index map (offset, voxel).
double exact_optical_depth(int nx, int ny, int nz, const std::vector<float>& values, double voxel_m,
                           const glm::dvec3& offset, double sigma, const glm::dvec3& eye, const glm::dvec3& dir,
                           double t_max) {
  const int n[3] = {nx, ny, nz};
  auto index = [&](double t) { return (eye + t * dir - offset) / voxel_m; };
  auto value = [&](int i, int j, int k) -> double {
    if (i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz) return 0.0;
    return values[i + nx * (j + ny * k)];
  };
  auto density = [&](double t) {
    const glm::dvec3 q = index(t);
    const glm::dvec3 b = glm::floor(q);
    const glm::dvec3 f = q - b;
    double sum = 0.0;
    for (int dz = 0; dz < 2; ++dz)
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx)
          sum += (dx ? f.x : 1 - f.x) * (dy ? f.y : 1 - f.y) * (dz ? f.z : 1 - f.z) *
                 value(int(b.x) + dx, int(b.y) + dy, int(b.z) + dz);
    return sum;
  };
  std::vector<double> cuts = {0.0, t_max};
  const glm::dvec3 q0 = index(0.0);
  const glm::dvec3 qd = dir / voxel_m;
  for (int a = 0; a < 3; ++a) {
    if (qd[a] == 0.0) continue;
    for (int plane = -2; plane <= n[a] + 1; ++plane) {
      const double t = (plane - q0[a]) / qd[a];
      if (t > 0.0 && t < t_max) cuts.push_back(t);
    }
  }
  std::sort(cuts.begin(), cuts.end());
  const double node = std::sqrt(0.6), w[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0}, x[3] = {-node, 0.0, node};
  double tau = 0.0;
  for (std::size_t s = 0; s + 1 < cuts.size(); ++s) {
    const double mid = 0.5 * (cuts[s] + cuts[s + 1]), half = 0.5 * (cuts[s + 1] - cuts[s]);
    for (int g = 0; g < 3; ++g) tau += w[g] * half * density(mid + half * x[g]);
  }
  return sigma * tau;
}

nr::CloudReferenceSettings steps(double view, double shadow) {
  nr::CloudReferenceSettings s;
  s.view_step_voxels = view;
  s.shadow_step_voxels = shadow;
  s.min_transmittance = 0.0;
  return s;
}

}  // namespace

// A box of n voxels of value rho: with the trilinear ramps (half a voxel of them at each face)
// the optical depth along an axis through a voxel centre is exactly sigma rho n voxel. Steps of
// 0.25 voxel put the ramps' kinks on step boundaries, so the midpoint rule is exact there.
TEST(CloudReference, AxisRayThroughBoxHasClosedFormAlpha) {
  const double voxel = 0.1, sigma = 3.0;
  const float rho = 0.7f;
  const glm::dvec3 offset(0.2, -0.1, 0.4);
  const std::vector<nr::CloudVolume> clouds = {box_cloud(6, 6, 8, rho, voxel, offset, grey(sigma, 0.9))};
  const glm::dvec3 eye = offset + voxel * glm::dvec3(3.0, 2.0, -20.0);
  const double expected = 1.0 - std::exp(-sigma * rho * 8 * voxel);
  const nr::CloudSample s = nr::cloud_reference_ray(clouds, {}, eye, {0, 0, 1}, steps(0.25, 0.5));
  EXPECT_NEAR(s.alpha, expected, 1e-12);
  // Unaligned steps: the kinks fall inside steps, an O(h^2) error per kink.
  const nr::CloudSample u = nr::cloud_reference_ray(clouds, {}, eye, {0, 0, 1}, steps(0.3, 0.5));
  EXPECT_NEAR(u.alpha, expected, 1e-3);
  // Two copies of the same cloud add their extinction.
  const std::vector<nr::CloudVolume> twice = {clouds[0], clouds[0]};
  EXPECT_NEAR(nr::cloud_reference_ray(twice, {}, eye, {0, 0, 1}, steps(0.25, 0.5)).alpha,
              1.0 - std::exp(-2.0 * sigma * rho * 8 * voxel), 1e-12);
  // The same ray as a camera's centre pixel (odd size: its ray is the view direction).
  nr::Camera cam;
  cam.eye = eye;
  cam.look_at = eye + glm::dvec3(0, 0, 1);
  cam.up = {0, 1, 0};
  cam.width = cam.height = 5;
  cam.fov_deg = 10.0;
  const nr::Image img = nr::render_cloud_reference(clouds, cam, {}, steps(0.25, 0.5));
  EXPECT_NEAR(img.pixel(2, 2)[3], expected, 1e-6);
  EXPECT_EQ(img.metadata.at("method"), "cloud-reference");
  EXPECT_EQ(img.metadata.at("view_step_voxels"), "0.25");
  EXPECT_EQ(img.metadata.at("shadow_step_voxels"), "0.5");
  EXPECT_NE(img.metadata.at("camera").find("fov_deg"), std::string::npos);
}

// An oblique ray through a random grid against the exact integral of the piecewise-trilinear
// density (Gauss-Legendre between plane crossings); the midpoint error falls as h^2.
TEST(CloudReference, ObliqueRayMatchesExactTrilinearIntegral) {
  const int nx = 6, ny = 5, nz = 7;
  const double voxel = 0.1, sigma = 4.0;
  const glm::dvec3 offset(0.3, -0.2, 0.15);
  const std::vector<float> values = random_values(nx * ny * nz, 11);
  const std::vector<nr::CloudVolume> clouds = {grid_cloud(nx, ny, nz, values, voxel, offset, grey(sigma, 0.5))};
  const glm::dvec3 eye = offset + glm::dvec3(-0.5, -0.3, -0.6);
  const glm::dvec3 dir = glm::normalize(offset + voxel * glm::dvec3(2.6, 2.3, 3.1) - eye);
  const double tau = exact_optical_depth(nx, ny, nz, values, voxel, offset, sigma, eye, dir, 10.0);
  ASSERT_GT(tau, 0.5);  // the ray really crosses the cloud
  const double exact = 1.0 - std::exp(-tau);
  const double coarse = nr::cloud_reference_ray(clouds, {}, eye, dir, steps(0.25, 0.5)).alpha;
  const double fine = nr::cloud_reference_ray(clouds, {}, eye, dir, steps(0.02, 0.5)).alpha;
  EXPECT_NEAR(coarse, exact, 2e-3);
  EXPECT_NEAR(fine, exact, 2e-5);
  EXPECT_LT(std::abs(fine - exact), std::abs(coarse - exact));
}

// A slab lit from straight above, seen from straight above: shadow and view rays cover the same
// density profile, so with tau = sigma rho n voxel (ramps included)
//   L = albedo E p(pi) (1 - exp(-2 tau)) / 2.
// With the sun at zenith angle acos(mu) in a laterally wide slab, the shadow path is 1/mu longer:
//   L = albedo E p(-mu) (1 - exp(-tau (1 + 1/mu))) / (1 + 1/mu).
TEST(CloudReference, SlabSingleScatteringMatchesClosedForm) {
  const double voxel = 0.05, sigma = 10.0, albedo = 0.8;
  const float rho = 0.6f;
  const int nx = 40, ny = 5, nz = 40;
  for (const double g : {0.0, 0.6, -0.3}) {
    nr::CloudOptics o = grey(sigma, albedo);
    o.phase.g_forward = g;
    const std::vector<nr::CloudVolume> clouds = {box_cloud(nx, ny, nz, rho, voxel, {0, 0, 0}, o)};
    const double tau = sigma * rho * ny * voxel;
    const glm::dvec3 eye = voxel * glm::dvec3(20.0, 30.0, 20.0);
    for (const double zenith_deg : {0.0, 45.0}) {
      const double mu = std::cos(zenith_deg * kPi / 180.0);
      nr::CloudLight sun;
      sun.direction_to_light = {std::sin(zenith_deg * kPi / 180.0), mu, 0.0};
      sun.irradiance_w_m2 = {2.0, 3.0, 4.0};
      const double k = 1.0 + 1.0 / mu;
      const double factor = albedo * hg(g, -mu) * (1.0 - std::exp(-tau * k)) / k;
      const nr::CloudSample s = nr::cloud_reference_ray(clouds, sun, eye, {0, -1, 0}, steps(0.1, 0.1));
      SCOPED_TRACE("g " + std::to_string(g) + " zenith " + std::to_string(zenith_deg));
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.radiance[c] / (sun.irradiance_w_m2[c] * factor), 1.0, 2e-3);
      EXPECT_NEAR(s.alpha, 1.0 - std::exp(-tau), 1e-12);
    }
  }
}

// Halving both steps changes a random volume's image (optical depth up to 1.2 per voxel) by less
// than 0.5 % (relative RMSE over covered pixels) after three halvings, and every halving changes
// it by less than half of what the previous one did (second order: measured 4.9 %, 0.86 %, 0.2 %).
TEST(CloudReference, ImageConvergesWhenStepsHalve) {
  const int n = 10;
  const double voxel = 0.1;
  const std::vector<nr::CloudVolume> clouds = {
      grid_cloud(n, n, n, random_values(n * n * n, 5), voxel, {-0.45, -0.45, -0.45}, grey(12.0, 0.9))};
  nr::Camera cam;
  cam.eye = {0.4, 0.3, 2.0};
  cam.look_at = {0, 0, 0};
  cam.up = {0, 1, 0};
  cam.fov_deg = 40;
  cam.width = cam.height = 24;
  nr::CloudLight sun;
  sun.direction_to_light = {0.6, 0.8, 0.3};
  std::vector<nr::Image> images;
  for (const double h : {1.0, 0.5, 0.25, 0.125})
    images.push_back(nr::render_cloud_reference(clouds, cam, sun, steps(h, 2 * h)));
  std::vector<double> change;
  for (std::size_t i = 0; i + 1 < images.size(); ++i)
    change.push_back(nr::compare_images(images[i], images[i + 1]).rel_rmse);
  std::cout << "relative RMSE change per halving: " << change[0] << ", " << change[1] << ", " << change[2] << "\n";
  EXPECT_LT(change[2], 5e-3);
  EXPECT_LT(change[1], 0.5 * change[0]);
  EXPECT_LT(change[2], 0.5 * change[1]);
}

// Ambient sky alone (no sun): the source over extinction is albedo L_amb everywhere, so
// L = albedo L_amb alpha per channel, and alpha ~ tau for a thin box.
TEST(CloudReference, AmbientAloneGivesAlbedoTimesAmbientTimesAlpha) {
  const double voxel = 0.1, sigma = 0.2;
  const float rho = 0.5f;
  nr::CloudOptics o = grey(sigma, 1.0);
  o.albedo = {0.9, 0.8, 0.7};
  o.ambient_radiance = {0.5, 1.0, 2.0};
  const std::vector<nr::CloudVolume> clouds = {box_cloud(6, 6, 6, rho, voxel, {0, 0, 0}, o)};
  nr::CloudLight dark;
  dark.irradiance_w_m2 = glm::dvec3(0.0);
  const glm::dvec3 eye = voxel * glm::dvec3(2.0, 3.0, -10.0);
  const nr::CloudSample s = nr::cloud_reference_ray(clouds, dark, eye, {0, 0, 1});
  const double tau = sigma * rho * 6 * voxel;
  EXPECT_NEAR(s.alpha, 1.0 - std::exp(-tau), 1e-12);
  EXPECT_NEAR(s.alpha, tau, tau * tau);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.radiance[c], o.albedo[c] * o.ambient_radiance[c] * s.alpha, 1e-14);
}

// The shadow ray alone: 1 where no cloud lies towards the light, exp(-sigma rho n voxel) through a
// box along an axis; the sun's irradiance does not enter.
TEST(CloudReference, LightTransmittanceOutsideShadowAndThroughBox) {
  const double voxel = 0.1, sigma = 2.5;
  const float rho = 0.8f;
  const std::vector<nr::CloudVolume> clouds = {box_cloud(4, 6, 4, rho, voxel, {0, 0, 0}, grey(sigma, 0.9))};
  nr::CloudLight sun;
  sun.direction_to_light = {0, 2, 0};  // normalised on use
  const glm::dvec3 below = voxel * glm::dvec3(1.0, -10.0, 2.0);
  EXPECT_NEAR(nr::cloud_light_transmittance(clouds, sun, below), std::exp(-sigma * rho * 6 * voxel), 1e-12);
  EXPECT_EQ(nr::cloud_light_transmittance(clouds, sun, voxel * glm::dvec3(1.0, 10.0, 2.0)), 1.0);   // above
  EXPECT_EQ(nr::cloud_light_transmittance(clouds, sun, voxel * glm::dvec3(10.0, -10.0, 2.0)), 1.0);  // beside
  EXPECT_EQ(nr::cloud_light_transmittance({}, sun, below), 1.0);
  sun.direction_to_light = {1, 0, 0};  // the same box, the light now to the side
  EXPECT_EQ(nr::cloud_light_transmittance(clouds, sun, below), 1.0);
  EXPECT_NEAR(nr::cloud_light_transmittance(clouds, sun, voxel * glm::dvec3(-5.0, 2.0, 1.0)),
              std::exp(-sigma * rho * 4 * voxel), 1e-12);
}

TEST(CloudReference, ProgressGrowsToOne) {
  const std::vector<nr::CloudVolume> clouds = {box_cloud(3, 3, 3, 1.0f, 0.1, {0, 0, 0}, grey(1.0, 0.9))};
  nr::Camera cam;
  cam.eye = {0.1, 0.1, 2.0};
  cam.look_at = {0.1, 0.1, 0.1};
  cam.width = 6;
  cam.height = 7;
  nr::CloudReferenceSettings s;
  std::vector<double> seen;
  s.progress = [&](double f) { seen.push_back(f); };
  s.threads = 2;
  nr::render_cloud_reference(clouds, cam, {}, s);
  ASSERT_EQ(seen.size(), 7u);
  for (std::size_t i = 1; i < seen.size(); ++i) EXPECT_GT(seen[i], seen[i - 1]);
  EXPECT_EQ(seen.back(), 1.0);
}

namespace {
template <class F>
void expect_invalid(F&& f, const std::string& field) {
  try {
    f();
    ADD_FAILURE() << "expected std::invalid_argument naming " << field;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}
}  // namespace

TEST(CloudReference, BadInputRejected) {
  const std::vector<nr::CloudVolume> clouds = {box_cloud(3, 3, 3, 1.0f, 0.1, {0, 0, 0}, grey(1.0, 0.9))};
  nr::Camera cam;
  cam.eye = {0.1, 0.1, 2.0};
  cam.look_at = {0.1, 0.1, 0.1};
  cam.width = cam.height = 4;
  const double nan = std::nan("");
  auto with = [](auto edit) {
    nr::CloudReferenceSettings s;
    edit(s);
    return s;
  };
  const std::vector<std::pair<nr::CloudReferenceSettings, std::string>> bad = {
      {with([](auto& s) { s.view_step_voxels = 0; }), "view_step_voxels"},
      {with([](auto& s) { s.view_step_voxels = 9; }), "view_step_voxels"},
      {with([&](auto& s) { s.view_step_voxels = nan; }), "view_step_voxels"},
      {with([](auto& s) { s.shadow_step_voxels = -1; }), "shadow_step_voxels"},
      {with([](auto& s) { s.shadow_step_voxels = INFINITY; }), "shadow_step_voxels"},
      {with([](auto& s) { s.min_transmittance = 0.2; }), "min_transmittance"},
      {with([&](auto& s) { s.min_transmittance = nan; }), "min_transmittance"},
      {with([](auto& s) { s.threads = -1; }), "threads"},
  };
  for (const auto& [s, field] : bad) {
    expect_invalid([&] { nr::validate(s); }, field);
    expect_invalid([&] { nr::render_cloud_reference(clouds, cam, {}, s); }, field);
    expect_invalid([&] { nr::cloud_reference_ray(clouds, {}, cam.eye, {0, 0, -1}, s); }, field);
  }
  expect_invalid([&] { nr::cloud_light_transmittance(clouds, {}, cam.eye, 0.0); }, "shadow_step_voxels");
  expect_invalid([&] { nr::render_cloud_reference({}, cam, {}); }, "clouds");
  expect_invalid([&] { nr::cloud_reference_ray(clouds, {}, cam.eye, {0, 0, 0}); }, "dir");
  nr::CloudLight no_light;
  no_light.direction_to_light = {0, 0, 0};
  expect_invalid([&] { nr::render_cloud_reference(clouds, cam, no_light); }, "direction_to_light");
  nr::Camera bad_cam = cam;
  bad_cam.width = 0;
  expect_invalid([&] { nr::render_cloud_reference(clouds, bad_cam, {}); }, "width");
  std::vector<nr::CloudVolume> bad_optics = clouds;
  bad_optics[0].optics.extinction_per_m = nan;
  expect_invalid([&] { nr::render_cloud_reference(bad_optics, cam, {}); }, "extinction_per_m");
}

// An infinite density makes the step integral inf / inf: the pixel is refused, not written.
TEST(CloudReference, NonFinitePixelRefused) {
  std::vector<nr::CloudVolume> clouds = {box_cloud(3, 3, 3, 1.0f, 0.1, {0, 0, 0}, grey(1.0, 0.9))};
  clouds[0].box.values[13] = INFINITY;
  nr::Camera cam;
  cam.eye = {0.1, 0.1, 2.0};
  cam.look_at = {0.1, 0.1, 0.1};
  cam.width = cam.height = 3;
  cam.fov_deg = 5;
  EXPECT_THROW(nr::render_cloud_reference(clouds, cam, {}), std::runtime_error);
}
