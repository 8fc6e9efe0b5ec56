// Exact ray-scene intersection: primitives against closed forms, the heightfield DDA against
// brute force over all its triangles, shadow rays, bulbs.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "nimbus/render/scene/intersect.hpp"
#include "nimbus/render/scene/scene.hpp"

namespace nr = nimbus::render;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

nr::Heightfield bumpy_field() {
  nr::Heightfield h;
  h.nx = 9;
  h.nz = 7;
  h.spacing_m = 1.5;
  h.x0_m = -6.0;
  h.z0_m = -4.0;
  for (int iz = 0; iz < h.nz; ++iz) {
    for (int ix = 0; ix < h.nx; ++ix) h.heights_m.push_back(std::sin(1.3 * ix) * std::cos(0.9 * iz) * 2.0 + 0.3 * ix);
  }
  return h;
}

// Independent ray-triangle test (plane hit, then same-side tests), for the brute force.
bool brute_triangle(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& a, const glm::dvec3& b,
                    const glm::dvec3& c, double& t) {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double denom = glm::dot(n, d);
  if (denom == 0.0) return false;
  t = glm::dot(n, a - o) / denom;
  const glm::dvec3 p = o + t * d;
  const double s0 = glm::dot(glm::cross(b - a, p - a), n), s1 = glm::dot(glm::cross(c - b, p - b), n),
               s2 = glm::dot(glm::cross(a - c, p - c), n);
  return s0 >= 0 && s1 >= 0 && s2 >= 0;
}

double brute_heightfield(const nr::Heightfield& h, const glm::dvec3& o, const glm::dvec3& d) {
  double best = kInf;
  auto v = [&](int ix, int iz) {
    return glm::dvec3{h.x0_m + ix * h.spacing_m, h.heights_m[iz * h.nx + ix], h.z0_m + iz * h.spacing_m};
  };
  for (int iz = 0; iz + 1 < h.nz; ++iz) {
    for (int ix = 0; ix + 1 < h.nx; ++ix) {
      // Diagonal from (ix, iz) to (ix+1, iz+1), as documented in scene.hpp.
      const glm::dvec3 tri[2][3] = {{v(ix, iz), v(ix + 1, iz), v(ix + 1, iz + 1)},
                                    {v(ix, iz), v(ix + 1, iz + 1), v(ix, iz + 1)}};
      for (const auto& t3 : tri) {
        double t;
        if (brute_triangle(o, d, t3[0], t3[1], t3[2], t) && t > 0 && t < best) best = t;
      }
    }
  }
  return best;
}

}  // namespace

TEST(Intersect, PlaneAndBox) {
  const nr::GroundPlane g{-1.0, {}};
  auto hp = nr::intersect_plane(g, {0, 2, 0}, {0.6, -0.8, 0}, 0.0, kInf);
  ASSERT_TRUE(hp);
  EXPECT_DOUBLE_EQ(hp->t, 3.75);
  EXPECT_FALSE(nr::intersect_plane(g, {0, 2, 0}, {1, 0, 0}, 0.0, kInf));
  EXPECT_FALSE(nr::intersect_plane(g, {0, 2, 0}, {0.6, -0.8, 0}, 0.0, 3.0));

  const nr::Box b{{1, 1, 1}, {2, 3, 4}, {}};
  auto hb = nr::intersect_box(b, {0, 2, 2}, {1, 0, 0}, 0.0, kInf);
  ASSERT_TRUE(hb);
  EXPECT_DOUBLE_EQ(hb->t, 1.0);
  EXPECT_EQ(hb->normal, glm::dvec3(-1, 0, 0));
  // From inside: the exit face, outward normal.
  hb = nr::intersect_box(b, {1.5, 2, 2}, {0, 0, -2}, 0.0, kInf);
  ASSERT_TRUE(hb);
  EXPECT_DOUBLE_EQ(hb->t, 0.5);
  EXPECT_EQ(hb->normal, glm::dvec3(0, 0, -1));
  // Axis-parallel rays outside a slab miss; a diagonal one enters through the top.
  EXPECT_FALSE(nr::intersect_box(b, {0, 0, 2}, {1, 0, 0}, 0.0, kInf));
  hb = nr::intersect_box(b, {1.5, 5, 2}, {0, -1, 0.1}, 0.0, kInf);
  ASSERT_TRUE(hb);
  EXPECT_DOUBLE_EQ(hb->t, 2.0);
  EXPECT_EQ(hb->normal, glm::dvec3(0, 1, 0));
}

TEST(Intersect, SphereIsStableFarAndNear) {
  // A unit sphere 1e6 m away: the naive discriminant loses all digits, the stable one not.
  auto h = nr::intersect_sphere({1e6, 0, 0}, 1.0, {0, 0, 0}, {1, 0, 0}, 0.0, kInf);
  ASSERT_TRUE(h);
  EXPECT_NEAR(h->t, 1e6 - 1.0, 1e-9);
  // Off-centre by 0.6: the chord's half length is 0.8.
  h = nr::intersect_sphere({1e6, 0.6, 0}, 1.0, {0, 0, 0}, {1, 0, 0}, 0.0, kInf);
  ASSERT_TRUE(h);
  EXPECT_NEAR(h->t, 1e6 - 0.8, 1e-9);
  EXPECT_NEAR(h->normal.x, -0.8, 1e-9);
  // Starting 1e-9 m outside the surface and leaving: no hit; entering: the near root ~1e-9.
  EXPECT_FALSE(nr::intersect_sphere({0, 0, 0}, 2.0, {0, 2.0 + 1e-9, 0}, {0, 1, 0}, 0.0, kInf));
  h = nr::intersect_sphere({0, 0, 0}, 2.0, {0, 2.0 + 1e-9, 0}, {0, -1, 0}, 0.0, kInf);
  ASSERT_TRUE(h);
  EXPECT_NEAR(h->t, 1e-9, 1e-15);
  // Non-unit direction: t in units of its length.
  h = nr::intersect_sphere({0, 0, 0}, 1.0, {-5, 0, 0}, {2, 0, 0}, 0.0, kInf);
  ASSERT_TRUE(h);
  EXPECT_DOUBLE_EQ(h->t, 2.0);
  EXPECT_FALSE(nr::intersect_sphere({0, 0, 0}, 1.0, {-5, 1.0001, 0}, {1, 0, 0}, 0.0, kInf));
}

TEST(Intersect, HeightfieldMatchesBruteForceOverAllTriangles) {
  const nr::Heightfield h = bumpy_field();
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int hits = 0;
  for (int i = 0; i < 3000; ++i) {
    const glm::dvec3 o{u(rng) * 10.0, 3.0 + 3.0 * u(rng), u(rng) * 8.0};
    glm::dvec3 d{u(rng), u(rng) - 0.4, u(rng)};
    if (i % 10 == 0) d = {0.0, -1.0, 0.0};            // vertical
    if (i % 10 == 1) d = {u(rng), -0.5, 0.0};          // along a grid row
    const double expect = brute_heightfield(h, o, d);
    const auto got = nr::intersect_heightfield(h, o, d, 0.0, kInf);
    if (std::isinf(expect)) {
      EXPECT_FALSE(got) << i;
      continue;
    }
    ++hits;
    ASSERT_TRUE(got) << i;
    EXPECT_NEAR(got->t, expect, 1e-9 * (1.0 + expect)) << i;
    EXPECT_GT(got->normal.y, 0.0);
    EXPECT_NEAR(glm::length(got->normal), 1.0, 1e-12);
  }
  EXPECT_GT(hits, 500);
}

TEST(Intersect, HeightfieldHeightIsTheTriangleSurface) {
  const nr::Heightfield h = bumpy_field();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> ux(h.x0_m, h.x0_m + (h.nx - 1) * h.spacing_m);
  std::uniform_real_distribution<double> uz(h.z0_m, h.z0_m + (h.nz - 1) * h.spacing_m);
  for (int i = 0; i < 500; ++i) {
    const double x = ux(rng), z = uz(rng);
    const auto y = nr::heightfield_height(h, x, z);
    ASSERT_TRUE(y);
    const auto hit = nr::intersect_heightfield(h, {x, 100.0, z}, {0, -1, 0}, 0.0, kInf);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(100.0 - hit->t, *y, 1e-9);
  }
  EXPECT_DOUBLE_EQ(*nr::heightfield_height(h, h.x0_m + 3 * h.spacing_m, h.z0_m + 2 * h.spacing_m),
                   h.heights_m[2 * h.nx + 3]);
  EXPECT_FALSE(nr::heightfield_height(h, h.x0_m - 0.1, 0.0));
}

TEST(Intersect, SceneNearestHitShadowRaysAndBulbs) {
  nr::Scene s;
  s.ground = nr::GroundPlane{0.0, {{0.1, 0.2, 0.3}}};
  s.boxes.push_back({{-1, 0, -1}, {1, 2, 1}, {{0.9, 0.9, 0.9}}});
  s.spheres.push_back({{0, 4, 0}, 1.0, {{0.5, 0.4, 0.3}}});
  s.lamps.push_back(nr::bulb_light({0, 8, 0}, glm::dvec3{10.0}, 0.5));
  // Straight down from above: sphere first, with its albedo.
  auto h = nr::intersect(s, {0, 20, 0}, {0, -1, 0});
  ASSERT_TRUE(h);
  EXPECT_DOUBLE_EQ(h->t, 15.0);
  EXPECT_EQ(h->albedo, glm::dvec3(0.5, 0.4, 0.3));
  h = nr::intersect(s, {3, 20, 0}, {0, -1, 0});
  ASSERT_TRUE(h);
  EXPECT_DOUBLE_EQ(h->t, 20.0);
  EXPECT_EQ(h->albedo, glm::dvec3(0.1, 0.2, 0.3));
  EXPECT_FALSE(nr::intersect(s, {3, 20, 0}, {0, -1, 0}, 19.0));
  // The bulb is not geometry and never occludes; the sphere does.
  EXPECT_FALSE(nr::intersect(s, {0, 10, 0}, {0, -1, 0}, 4.0));
  EXPECT_FALSE(nr::occluded(s, {0, 10, 0}, {0, 6, 0}));
  EXPECT_TRUE(nr::occluded(s, {0, 8, 0}, {0, 2.5, 0}));
  EXPECT_FALSE(nr::occluded(s, {0, 8, 0}, {5, 0.1, 0}));
  EXPECT_TRUE(nr::occluded_toward(s, {0, 2.5, 0}, {0, 1, 0}));
  EXPECT_FALSE(nr::occluded_toward(s, {5, 2.5, 0}, {0, 1, 0}));
  EXPECT_TRUE(nr::occluded_toward(s, {5, 2.5, 0}, {0, -1, 0}));  // the ground plane
  auto b = nr::intersect_bulbs(s, {0, 10, 0}, {0, -1, 0});
  ASSERT_TRUE(b);
  EXPECT_DOUBLE_EQ(b->t, 1.5);
  EXPECT_EQ(b->light, 0u);
  EXPECT_FALSE(nr::intersect_bulbs(s, {0, 10, 0}, {0, -1, 0}, 1.0));
}
