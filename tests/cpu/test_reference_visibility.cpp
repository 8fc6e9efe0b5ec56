// The reference's visibility search: a box's shadow region from a point light and from the
// sun is exactly the set of points whose shadow ray meets the box (so culling by it never
// misses a shadow), and lit intervals land on the analytic shadow boundaries.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "nimbus/render/scene/intersect.hpp"
#include "nimbus/render/reference/reference_visibility.hpp"

namespace nr = nimbus::render;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct RandomCase {
  nr::Box box;
  glm::dvec3 o, d;
};

RandomCase random_case(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  RandomCase c;
  const glm::dvec3 centre{u(rng) * 3, u(rng) * 3, u(rng) * 3};
  const glm::dvec3 half{0.2 + std::abs(u(rng)) * 2, 0.2 + std::abs(u(rng)) * 2, 0.2 + std::abs(u(rng)) * 2};
  c.box = {centre - half, centre + half, {}};
  c.o = {u(rng) * 12, u(rng) * 12, u(rng) * 12};
  c.d = glm::normalize(glm::dvec3{u(rng), u(rng), u(rng)} + 0.3 * glm::normalize(centre - c.o));
  return c;
}

bool inside(const nr::Box& b, const glm::dvec3& p) {
  return glm::all(glm::greaterThan(p, b.min_m)) && glm::all(glm::lessThan(p, b.max_m));
}

}  // namespace

TEST(ReferenceVisibility, PointShadowRegionIsExactlyTheBoxShadow) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int shadowed = 0, outside = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const RandomCase c = random_case(rng);
    const glm::dvec3 light{u(rng) * 8, u(rng) * 8, u(rng) * 8};
    if (inside(c.box, light) || inside(c.box, c.o)) continue;
    const nr::ShadowRegion region = nr::point_shadow_region(light, c.box.min_m, c.box.max_m);
    ASSERT_FALSE(region.everywhere);
    double a = 0.0, b = 40.0;
    const bool any = nr::clip_to_region(region, c.o, c.d, a, b);
    for (int i = 0; i <= 400; ++i) {
      const double x = 40.0 * i / 400;
      const glm::dvec3 p = c.o + x * c.d;
      if (inside(c.box, p)) continue;
      const bool hit = nr::intersect_box(c.box, p, light - p, 0.0, 1.0).has_value();
      const bool in_range = any && x >= a - 1e-9 && x <= b + 1e-9;
      const double margin = any ? std::min(std::abs(x - a), std::abs(x - b)) : kInf;
      if (margin < 1e-7) continue;  // on the boundary either answer is right
      EXPECT_EQ(hit, in_range) << "trial " << trial << " x " << x;
      shadowed += hit;
      outside += !in_range;
    }
  }
  EXPECT_GT(shadowed, 1000);
  EXPECT_GT(outside, 1000);
  // A light inside the box shadows everything.
  EXPECT_TRUE(nr::point_shadow_region({0, 0, 0}, {-1, -1, -1}, {1, 1, 1}).everywhere);
}

TEST(ReferenceVisibility, SunShadowRangeIsExactlyTheBoxShadow) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int shadowed = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const RandomCase c = random_case(rng);
    const glm::dvec3 sun = glm::normalize(glm::dvec3{u(rng), u(rng), u(rng)});
    double a, b;
    const bool any = nr::sun_shadow_range(c.o, c.d, sun, c.box.min_m, c.box.max_m, a, b);
    for (int i = 0; i <= 400; ++i) {
      const double x = -20.0 + 60.0 * i / 400;
      const glm::dvec3 p = c.o + x * c.d;
      const bool hit = inside(c.box, p) || nr::intersect_box(c.box, p, sun, 0.0, kInf).has_value();
      const double margin = any ? std::min(std::abs(x - a), std::abs(x - b)) : kInf;
      if (margin < 1e-7) continue;
      EXPECT_EQ(hit, any && x >= a && x <= b) << "trial " << trial << " x " << x;
      shadowed += hit;
    }
  }
  EXPECT_GT(shadowed, 500);
}

TEST(ReferenceVisibility, LitIntervalsEndOnTheAnalyticShadowBoundaries) {
  // Light at (0, 5, 0), view ray along +x at y = 0; a plate 2.5 <= y <= 2.6 over
  // -6 <= x <= -3 shadows x in [-6 / 0.48, -6], a sphere of radius 0.5 at (4, 2.5, 0) shadows
  // x where the ray enters/leaves its tangent cone: distance from (4,2.5) to the line from
  // (x, 0) to (0, 5) equals 0.5.
  nr::Scene s;
  s.boxes.push_back({{-6.0, 2.5, -1.0}, {-3.0, 2.6, 1.0}, {}});
  s.spheres.push_back({{4.0, 2.5, 0.0}, 0.5, {}});
  const glm::dvec3 light{0.0, 5.0, 0.0}, o{-30.0, 0.0, 0.0}, d{1.0, 0.0, 0.0};
  const nr::SceneTracer tracer(s);
  std::vector<nr::ShadowRegion> regions;
  for (std::size_t k = 0; k < tracer.occluder_count(); ++k) {
    glm::dvec3 lo, hi;
    tracer.occluder_bounds(k, lo, hi);
    regions.push_back(nr::point_shadow_region(light, lo, hi));
  }
  const nr::Intervals lit = nr::point_light_lit_intervals(tracer, regions, light, o, d, 60.0, 256);
  ASSERT_EQ(lit.size(), 3u);
  // Sphere shadow ends: solve |cross(C - X, L - X)| / |L - X| = r for X = (x, 0, 0).
  auto dist = [&](double x) {
    const glm::dvec3 X{x, 0, 0}, C{4.0, 2.5, 0.0};
    return glm::length(glm::cross(C - X, light - X)) / glm::length(light - X) - 0.5;
  };
  auto root = [&](double lo, double hi) {
    for (int i = 0; i < 200; ++i) {
      const double m = 0.5 * (lo + hi);
      ((dist(lo) > 0) == (dist(m) > 0) ? lo : hi) = m;
    }
    return 0.5 * (lo + hi);
  };
  const double s0 = root(4.5, 8.0), s1 = root(8.0, 20.0);  // dist < 0 around x = 8
  ASSERT_LT(dist(8.0), 0.0);
  const double expect[3][2] = {{0.0, -6.0 / 0.48 + 30.0}, {-6.0 + 30.0, s0 + 30.0}, {s1 + 30.0, 60.0}};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(lit[i].first, expect[i][0], 1e-7) << i;
    EXPECT_NEAR(lit[i].second, expect[i][1], 1e-7) << i;
  }
}
