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
  const nr::CloudSample s = nr::cloud_reference_ray(clouds, nr::Light{}, eye, {0, 0, 1}, steps(0.25, 0.5));
  EXPECT_NEAR(s.alpha, expected, 1e-12);
  // Unaligned steps: the kinks fall inside steps, an O(h^2) error per kink.
  const nr::CloudSample u = nr::cloud_reference_ray(clouds, nr::Light{}, eye, {0, 0, 1}, steps(0.3, 0.5));
  EXPECT_NEAR(u.alpha, expected, 1e-3);
  // Two copies of the same cloud add their extinction.
  const std::vector<nr::CloudVolume> twice = {clouds[0], clouds[0]};
  EXPECT_NEAR(nr::cloud_reference_ray(twice, nr::Light{}, eye, {0, 0, 1}, steps(0.25, 0.5)).alpha,
              1.0 - std::exp(-2.0 * sigma * rho * 8 * voxel), 1e-12);
  // The same ray as a camera's centre pixel (odd size: its ray is the view direction).
  nr::Camera cam;
  cam.eye = eye;
  cam.look_at = eye + glm::dvec3(0, 0, 1);
  cam.up = {0, 1, 0};
  cam.width = cam.height = 5;
  cam.fov_deg = 10.0;
  const nr::Image img = nr::render_cloud_reference(clouds, cam, nr::Light{}, steps(0.25, 0.5));
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
  const double coarse = nr::cloud_reference_ray(clouds, nr::Light{}, eye, dir, steps(0.25, 0.5)).alpha;
  const double fine = nr::cloud_reference_ray(clouds, nr::Light{}, eye, dir, steps(0.02, 0.5)).alpha;
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
    o.phase = nr::Phase{nr::PhaseKind::HenyeyGreenstein, g};
    const std::vector<nr::CloudVolume> clouds = {box_cloud(nx, ny, nz, rho, voxel, {0, 0, 0}, o)};
    const double tau = sigma * rho * ny * voxel;
    const glm::dvec3 eye = voxel * glm::dvec3(20.0, 30.0, 20.0);
    for (const double zenith_deg : {0.0, 45.0}) {
      const double mu = std::cos(zenith_deg * kPi / 180.0);
      nr::Light sun;
      sun.direction_to_sun = {std::sin(zenith_deg * kPi / 180.0), mu, 0.0};
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
  nr::Light sun;
  sun.direction_to_sun = {0.6, 0.8, 0.3};
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
  nr::Light dark;
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
  nr::Light sun;
  sun.direction_to_sun = {0, 2, 0};  // normalised on use
  const glm::dvec3 below = voxel * glm::dvec3(1.0, -10.0, 2.0);
  EXPECT_NEAR(nr::cloud_light_transmittance(clouds, sun, below), std::exp(-sigma * rho * 6 * voxel), 1e-12);
  EXPECT_EQ(nr::cloud_light_transmittance(clouds, sun, voxel * glm::dvec3(1.0, 10.0, 2.0)), 1.0);   // above
  EXPECT_EQ(nr::cloud_light_transmittance(clouds, sun, voxel * glm::dvec3(10.0, -10.0, 2.0)), 1.0);  // beside
  EXPECT_EQ(nr::cloud_light_transmittance({}, sun, below), 1.0);
  sun.direction_to_sun = {1, 0, 0};  // the same box, the light now to the side
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
  nr::render_cloud_reference(clouds, cam, nr::Light{}, s);
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

// A lamp on the axis of a homogeneous box (rho0 on the voxel centres 0 .. n-1, trilinear ramps
// one voxel wide outside them), the eye on the same axis. Every view and shadow ray lies on the
// axis, so the density profile rho(z) is piecewise linear and
//   back-lit (lamp beyond the box, at z = Lz): view + shadow depth is the whole tau, and
//     L = sigma a p(1) I e^{-tau} int rho(z) / (Lz - z)^2 dz,
//   which is closed: int (c0 + c1 z) / (Lz - z)^2 dz = A / (Lz - z) + c1 ln(Lz - z), A = c0 + c1 Lz;
//   front-lit (lamp between the eye and the box, at z = Lz): both paths see tau(z), and
//     L = sigma a p(-1) I int rho(z) e^{-2 tau(z)} / (z - Lz)^2 dz,
//   integrated here by Gauss-Legendre on fine pieces with tau(z) in closed form.
namespace {

struct AxisBox {
  double voxel = 0.1, sigma = 2.0, albedo = 0.9;
  float rho0 = 0.8f;
  int n = 10;  // voxels along z
  // The profile's pieces: ramp up over [-v, 0], flat to (n-1) v, ramp down to n v.
  double z_lo() const { return -voxel; }
  double z_hi() const { return n * voxel; }
  double rho(double z) const {
    const double top = (n - 1) * voxel;
    if (z <= z_lo() || z >= z_hi()) return 0.0;
    if (z < 0.0) return rho0 * (z - z_lo()) / voxel;
    if (z > top) return rho0 * (z_hi() - z) / voxel;
    return rho0;
  }
  double tau_to(double z) const {  // sigma int_{z_lo}^{z} rho
    const double v = voxel, top = (n - 1) * voxel;
    if (z <= z_lo()) return 0.0;
    if (z < 0.0) return sigma * rho0 * (z - z_lo()) * (z - z_lo()) / (2.0 * v);
    if (z <= top) return sigma * rho0 * (0.5 * v + z);
    if (z < z_hi()) return sigma * rho0 * (n * v - (z_hi() - z) * (z_hi() - z) / (2.0 * v));
    return sigma * rho0 * n * v;
  }
};

double back_lit_integral(const AxisBox& b, double Lz) {  // int rho / (Lz - z)^2, closed form
  const double v = b.voxel, top = (b.n - 1) * v;
  auto piece = [&](double c0, double c1, double za, double zb) {
    const double A = c0 + c1 * Lz;
    auto F = [&](double z) { return A / (Lz - z) + c1 * std::log(Lz - z); };
    return F(zb) - F(za);
  };
  return piece(-b.rho0 * b.z_lo() / v, b.rho0 / v, b.z_lo(), 0.0) + piece(b.rho0, 0.0, 0.0, top) +
         piece(b.rho0 * b.z_hi() / v, -b.rho0 / v, top, b.z_hi());
}

double front_lit_integral(const AxisBox& b, double Lz) {  // int rho e^{-2 tau} / (z - Lz)^2
  const double node = std::sqrt(0.6), w[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0}, x[3] = {-node, 0.0, node};
  const double cuts[4] = {b.z_lo(), 0.0, (b.n - 1) * b.voxel, b.z_hi()};
  double sum = 0.0;
  for (int p = 0; p < 3; ++p) {
    const int m = 400;
    const double h = (cuts[p + 1] - cuts[p]) / m;
    for (int k = 0; k < m; ++k) {
      const double mid = cuts[p] + (k + 0.5) * h;
      for (int g = 0; g < 3; ++g) {
        const double z = mid + 0.5 * h * x[g];
        sum += w[g] * 0.5 * h * b.rho(z) * std::exp(-2.0 * b.tau_to(z)) / ((z - Lz) * (z - Lz));
      }
    }
  }
  return sum;
}

}  // namespace

TEST(CloudReference, LampOnTheAxisOfABoxMatchesClosedForms) {
  const AxisBox b;
  const double centre = 2.5 * b.voxel;  // between voxel centres 2 and 3 of 6: the full rho0 across
  const glm::dvec3 eye(centre, centre, -1.0);
  const glm::dvec3 I(40.0, 50.0, 60.0);
  for (const double g : {0.0, 0.5}) {
    nr::CloudOptics o = grey(b.sigma, b.albedo);
    o.phase = nr::Phase{nr::PhaseKind::HenyeyGreenstein, g};
    const std::vector<nr::CloudVolume> clouds = {box_cloud(6, 6, b.n, b.rho0, b.voxel, {0, 0, 0}, o)};
    const double tau = b.sigma * b.rho0 * b.n * b.voxel;
    SCOPED_TRACE("g " + std::to_string(g));
    {
      const double Lz = 2.0;  // back-lit: the lamp beyond the box, light travelling towards the eye
      const nr::Light lamp = nr::point_light({centre, centre, Lz}, I);
      const nr::CloudSample s = nr::cloud_reference_ray(clouds, lamp, eye, {0, 0, 1}, steps(0.25, 0.1));
      const double k = b.sigma * b.albedo * hg(g, 1.0) * std::exp(-tau) * back_lit_integral(b, Lz);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.radiance[c] / (I[c] * k), 1.0, 2e-3) << "back-lit channel " << c;
      EXPECT_NEAR(s.alpha, 1.0 - std::exp(-tau), 1e-12);
      // The inverse square: the lamp twice as far (from the box's middle) is about four times dimmer.
      const nr::Light far = nr::point_light({centre, centre, 0.5 + 2.0 * (Lz - 0.5)}, I);
      const double k_far = b.sigma * b.albedo * hg(g, 1.0) * std::exp(-tau) * back_lit_integral(b, 0.5 + 2.0 * (Lz - 0.5));
      EXPECT_NEAR(nr::cloud_reference_ray(clouds, far, eye, {0, 0, 1}, steps(0.25, 0.1)).radiance[0] / (I[0] * k_far), 1.0, 2e-3);
      // A spot aimed at the box lights it as the lamp does; aimed away, not at all.
      const nr::Light at = nr::point_light(lamp.position_m, I, {0, 0, -1}, 0.1, 0.2);
      const nr::Light away = nr::point_light(lamp.position_m, I, {0, 0, 1}, 0.1, 0.2);
      EXPECT_NEAR(nr::cloud_reference_ray(clouds, at, eye, {0, 0, 1}, steps(0.25, 0.1)).radiance[1], s.radiance[1], 1e-12);
      const nr::CloudSample dark = nr::cloud_reference_ray(clouds, away, eye, {0, 0, 1}, steps(0.25, 0.1));
      EXPECT_EQ(dark.radiance[1], 0.0);
      EXPECT_NEAR(dark.alpha, s.alpha, 1e-15);
      // Two lamps add.
      const nr::CloudSample both =
          nr::cloud_reference_ray(clouds, std::vector<nr::Light>{lamp, far}, eye, {0, 0, 1}, steps(0.25, 0.1));
      EXPECT_NEAR(both.radiance[2] / (I[2] * (k + k_far)), 1.0, 2e-3);
    }
    {
      const double Lz = -0.5;  // front-lit: the lamp between the eye and the box
      const nr::Light lamp = nr::point_light({centre, centre, Lz}, I);
      const nr::CloudSample s = nr::cloud_reference_ray(clouds, lamp, eye, {0, 0, 1}, steps(0.25, 0.1));
      const double k = b.sigma * b.albedo * hg(g, -1.0) * front_lit_integral(b, Lz);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.radiance[c] / (I[c] * k), 1.0, 2e-3) << "front-lit channel " << c;
    }
  }
}

// The shadow ray to a lamp ends at the lamp: a lamp inside a box is dimmed by the density between
// it and the point only.
TEST(CloudReference, ShadowRayToALampInsideABoxEndsAtTheLamp) {
  const AxisBox b;
  const std::vector<nr::CloudVolume> clouds = {box_cloud(6, 6, b.n, b.rho0, b.voxel, {0, 0, 0}, grey(b.sigma, 0.9))};
  const double centre = 2.5 * b.voxel;
  const nr::Light lamp = nr::point_light({centre, centre, 0.7}, glm::dvec3(1.0));
  for (const double z : {0.1, 0.4, 0.65}) {
    EXPECT_NEAR(nr::cloud_light_transmittance(clouds, lamp, {centre, centre, z}, 0.1),
                std::exp(-(b.tau_to(0.7) - b.tau_to(z))), 1e-12)
        << "z " << z;
  }
  // Beyond the box the whole depth between lamp and box's face counts, not the box behind the lamp.
  EXPECT_NEAR(nr::cloud_light_transmittance(clouds, lamp, {centre, centre, -2.0}, 0.1), std::exp(-b.tau_to(0.7)), 1e-12);
}

// The light model itself: inverse square, the spot's smoothstep, the floor on the distance, and
// the ranking of lights by their irradiance at a point.
TEST(Light, InverseSquareSpotFloorAndRanking) {
  const nr::Light lamp = nr::point_light({0, 4, 0}, glm::dvec3(100.0));
  const nr::LightAtPoint a = nr::light_at(lamp, {0, 0, 0});
  EXPECT_NEAR(a.irradiance_w_m2.x, 100.0 / 16.0, 1e-12);
  EXPECT_NEAR(a.distance_m, 4.0, 1e-15);
  EXPECT_NEAR(a.to_light.y, 1.0, 1e-15);
  EXPECT_NEAR(nr::light_at(lamp, {0, 4, 0}).irradiance_w_m2.x, 100.0 / (1e-3 * 1e-3), 1e-3);  // at the lamp: the floor
  // Spot pointing down, full within 20 degrees, none beyond 40: at 30 degrees, cos halfway -> 0.5.
  const double inner = 20.0 * kPi / 180.0, outer = 40.0 * kPi / 180.0;
  const nr::Light spot = nr::point_light({0, 0, 0}, glm::dvec3(1.0), {0, -1, 0}, inner, outer);
  const double c_mid = 0.5 * (std::cos(inner) + std::cos(outer));
  const double s_mid = std::sqrt(1.0 - c_mid * c_mid);
  EXPECT_NEAR(nr::spot_weight(spot, {s_mid, -c_mid, 0}), 0.5, 1e-12);
  EXPECT_EQ(nr::spot_weight(spot, {0, -1, 0}), 1.0);
  EXPECT_EQ(nr::spot_weight(spot, {1, 0, 0}), 0.0);
  EXPECT_EQ(nr::spot_weight(lamp, {1, 0, 0}), 1.0);
  nr::Light sun;
  sun.irradiance_w_m2 = glm::dvec3(1.0);  // 1 W m^-2, against the lamps' 100 / r^2
  const std::vector<nr::Light> lights = {sun, lamp, nr::point_light({0, 2, 0}, glm::dvec3(100.0))};
  EXPECT_EQ(nr::strongest_lights(lights, {0, 0, 0}, 2), (std::vector<int>{2, 1}));
  EXPECT_EQ(nr::strongest_lights(lights, {0, -40, 0}, 5), (std::vector<int>{0, 2, 1}));
  nr::Light bad = nr::point_light({0, 0, 0}, glm::dvec3(1.0), {0, -1, 0}, 0.5, 0.2);
  expect_invalid([&] { nr::validate(bad); }, "spot");
  bad = nr::point_light({0, NAN, 0}, glm::dvec3(1.0));
  expect_invalid([&] { nr::validate(bad); }, "position_m");
  bad = nr::point_light({0, 0, 0}, glm::dvec3(-1.0));
  expect_invalid([&] { nr::validate(bad); }, "intensity_w_sr");
  bad.intensity_w_sr = glm::dvec3(1.0);
  bad.min_distance_m = 0.0;
  expect_invalid([&] { nr::validate(bad); }, "min_distance_m");
}

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
    expect_invalid([&] { nr::render_cloud_reference(clouds, cam, nr::Light{}, s); }, field);
    expect_invalid([&] { nr::cloud_reference_ray(clouds, nr::Light{}, cam.eye, {0, 0, -1}, s); }, field);
  }
  expect_invalid([&] { nr::cloud_light_transmittance(clouds, nr::Light{}, cam.eye, 0.0); }, "shadow_step_voxels");
  expect_invalid([&] { nr::render_cloud_reference({}, cam, nr::Light{}); }, "clouds");
  expect_invalid([&] { nr::cloud_reference_ray(clouds, nr::Light{}, cam.eye, {0, 0, 0}); }, "dir");
  nr::Light no_light;
  no_light.direction_to_sun = {0, 0, 0};
  expect_invalid([&] { nr::render_cloud_reference(clouds, cam, no_light); }, "direction_to_sun");
  nr::Camera bad_cam = cam;
  bad_cam.width = 0;
  expect_invalid([&] { nr::render_cloud_reference(clouds, bad_cam, nr::Light{}); }, "width");
  std::vector<nr::CloudVolume> bad_optics = clouds;
  bad_optics[0].optics.extinction_per_m = nan;
  expect_invalid([&] { nr::render_cloud_reference(bad_optics, cam, nr::Light{}); }, "extinction_per_m");
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
  EXPECT_THROW(nr::render_cloud_reference(clouds, cam, nr::Light{}), std::runtime_error);
}
