// Cloud fields (cloud_field.hpp) and what they rest on: the layout's power law, coverage and
// spacing; fractal outlines that scale with the shape; the shape index against brute force;
// shear and fibres; and the sub-box property (a field is a pure function of world position).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <random>

#include "nimbus/volume/cloud_field.hpp"
#include "support/cloud_stats.hpp"
#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/preset.hpp"
#include "nimbus/volume/shape_index.hpp"

namespace nimbus::volume {
namespace {

using test::CloudOutline;
using test::PowerLawFit;
using test::area_exponent;

TEST(CloudField, LayoutFollowsItsPowerLawCoversItsShareAndNeverStacks) {
  CloudFieldParams p;
  p.size_m = {40000.0, 40000.0};
  p.coverage = 0.3;
  p.seed = 5;
  const std::vector<FieldCloud> a = field_layout(p), b = field_layout(p);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) ASSERT_EQ(std::memcmp(&a[i], &b[i], sizeof(FieldCloud)), 0) << "layout is not a pure function";
  double covered = 0.0;
  std::vector<CloudOutline> outlines;
  int humilis = 0;
  for (const FieldCloud& c : a) {
    ASSERT_GE(c.diameter_m, p.min_diameter_m);
    ASSERT_LE(c.diameter_m, p.max_diameter_m);
    ASSERT_GE(c.center_m.x, -20000.0);
    ASSERT_LE(c.center_m.y, 20000.0);
    const double area = std::numbers::pi / 4 * c.diameter_m * c.diameter_m;
    covered += area;
    outlines.push_back({int64_t(area), area, std::sqrt(area), false});
    humilis += c.species == Species::Humilis;
  }
  const double share = covered / (p.size_m.x * p.size_m.y);
  std::printf("layout: %zu clouds, footprints cover %.3f (asked %.2f), humilis %.3f (asked 0.6)\n", a.size(), share,
              p.coverage, double(humilis) / a.size());
  EXPECT_NEAR(share, p.coverage, 0.03);  // a few small clouds may find no room
  EXPECT_NEAR(double(humilis) / a.size(), 0.6, 0.05);
  // No footprint overlaps another (brute force over all pairs nearby).
  for (size_t i = 0; i < a.size(); ++i)
    for (size_t j = i + 1; j < a.size(); ++j) {
      const glm::dvec2 d = a[i].center_m - a[j].center_m;
      const double r = 0.5 * (a[i].diameter_m + a[j].diameter_m);
      ASSERT_GE(d.x * d.x + d.y * d.y, r * r * (1 - 1e-12)) << "clouds " << i << " and " << j << " stack";
    }
  // The footprints' areas follow dn/dlog a ~ a^-b with b = size_exponent.
  const PowerLawFit fit = area_exponent(outlines, 5, 24, 1);
  std::printf("layout area exponent %.3f +- %.3f over %d bins (asked %.2f)\n", fit.exponent, fit.standard_error,
              fit.points, p.size_exponent);
  EXPECT_NEAR(fit.exponent, p.size_exponent, 0.12);
  // Another seed, another layout.
  CloudFieldParams q = p;
  q.seed = 6;
  EXPECT_NE(field_layout(q).front().center_m.x, a.front().center_m.x);
}

TEST(CloudField, BadParametersAndRunawayLayoutsAreRefusedByName) {
  auto refuses = [](CloudFieldParams p, const char* what) {
    try {
      field_layout(p);
      ADD_FAILURE() << "accepted: " << what;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  CloudFieldParams p;
  p.coverage = 0.0;
  refuses(p, "coverage");
  p = {};
  p.size_exponent = std::nan("");
  refuses(p, "size_exponent");
  p = {};
  p.max_diameter_m = 50.0;
  refuses(p, "max_diameter");
  p = {};
  p.species.clear();
  refuses(p, "species");
  p = {};
  p.roughness = 2.0;
  refuses(p, "roughness");
  p = {};
  p.size_m = {1e6, 1e6};
  p.min_diameter_m = 10.0;
  p.max_diameter_m = 20.0;
  refuses(p, "clouds would be placed");
}

TEST(CloudField, RoughOutlinesScaleWithTheShapeAndStayInTheirBounds) {
  Shape s;
  s.center = {100.0, -40.0, 1500.0};
  s.size = {300.0, 250.0, 200.0};
  s.falloff = 0.4;
  s.roughness = 0.6;
  s.roughness_seed = 77;
  Shape big = s;
  big.size *= 3.0;
  std::mt19937_64 gen(3);
  std::uniform_real_distribution<double> u(-1.8, 1.8);
  const Aabb box = shape_bounds(s);
  int inside = 0, differs = 0;
  Shape smooth = s;
  smooth.roughness = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const glm::dvec3 off(u(gen) * s.size.x, u(gen) * s.size.y, u(gen) * s.size.z);
    const glm::dvec3 p = s.center + off;
    const double c = shape_coverage(s, p);
    ASSERT_GE(c, 0.0);
    ASSERT_LE(c, s.weight);
    const bool in_box = p.x >= box.lo.x && p.x <= box.hi.x && p.y >= box.lo.y && p.y <= box.hi.y && p.z >= box.lo.z &&
                        p.z <= box.hi.z;
    if (!in_box) ASSERT_EQ(c, 0.0) << "coverage outside the bounds";
    if (c > 0.0 && shape_distance_bound(s, p) > 0.0) ADD_FAILURE() << "distance bound > 0 where coverage > 0";
    inside += c > 0.0;
    differs += std::fabs(c - shape_coverage(smooth, p)) > 1e-3;
    // Self-similar: the same point scaled about the centre sees the same coverage.
    ASSERT_NEAR(shape_coverage(big, s.center + 3.0 * off), c, 1e-5);
  }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(differs, 1000) << "roughness changed nothing";
}

TEST(CloudField, ShapeIndexFindsExactlyTheShapesHoldingAPoint) {
  CloudFieldParams p;
  p.size_m = {8000.0, 6000.0};
  const std::vector<Shape> shapes = field_shapes(p, 1000.0);
  const ShapeIndex index(shapes);
  std::mt19937_64 gen(9);
  std::uniform_real_distribution<double> ux(-4500, 4500), uy(-3500, 3500), uz(800, 2500);
  for (int i = 0; i < 5000; ++i) {
    const glm::dvec3 q(ux(gen), uy(gen), uz(gen));
    std::vector<uint32_t> want, got;
    for (uint32_t k = 0; k < shapes.size(); ++k) {
      const Aabb b = shape_bounds(shapes[k]);
      if (q.x >= b.lo.x && q.x <= b.hi.x && q.y >= b.lo.y && q.y <= b.hi.y && q.z >= b.lo.z && q.z <= b.hi.z) want.push_back(k);
    }
    index.visit(q, [&](uint32_t k) { got.push_back(k); });
    std::sort(got.begin(), got.end());
    ASSERT_EQ(got, want) << "at (" << q.x << ", " << q.y << ", " << q.z << ")";
  }
}

CloudParams small_field() {
  nlohmann::json doc = load_preset("cumulus-field");
  CloudParams p = cloud_from_json(doc.at("cloud"), "cumulus-field");
  p.field->size_m = {3000.0, 3000.0};
  return p;
}

TEST(CloudField, AnySubBoxGeneratedAloneEqualsTheWhole) {
  const CloudParams p = small_field();
  GenerateOptions o;
  o.voxel_size = 40.0;
  o.time = 37.0;
  const auto whole = generate_density(p, o);
  ASSERT_GT(whole->activeVoxelCount(), 3000u);
  // Boxes that cut through clouds, leaf blocks and the base, one of them a single voxel thick.
  const openvdb::CoordBBox boxes[] = {{{-13, -20, 20}, {9, 4, 41}}, {{0, 0, 0}, {40, 40, 80}}, {{-40, 5, 0}, {40, 5, 80}}};
  for (const auto& box : boxes) {
    GenerateOptions c = o;
    c.clip = box;
    const auto part = generate_density(p, c);
    int64_t in_box = 0;
    for (auto v = whole->cbeginValueOn(); v; ++v) in_box += box.isInside(v.getCoord());
    ASSERT_EQ(int64_t(part->activeVoxelCount()), in_box) << box;
    ASSERT_GT(in_box, 0) << box;
    const auto acc = whole->getConstAccessor();
    for (auto v = part->cbeginValueOn(); v; ++v) {
      ASSERT_TRUE(box.isInside(v.getCoord()));
      const float w = acc.getValue(v.getCoord());
      ASSERT_EQ(std::memcmp(&w, &*v, sizeof(float)), 0) << v.getCoord();
    }
  }
}

TEST(CloudField, ShearLeansTheCloudByItsSlope) {
  // With no displacement, the sheared model at p equals the upright one at p moved back by
  // shear * (z - base).
  CloudParams p = small_field();
  p.field->periodic = false;  // a periodic field's bounds are its tile, whatever the lean
  p.displacement = 0.0;
  p.wind = glm::dvec3(0.0);  // so both paths round alike
  p.shear = glm::dvec2(0.0);  // the preset leans already
  CloudParams s = p;
  s.shear = {0.4, -0.25};
  const CloudModel upright(p, 20.0, 12.0), leaning(s, 20.0, 12.0);
  std::mt19937_64 gen(4);
  std::uniform_real_distribution<double> ux(-1500, 1500), uz(1000, 2000);
  int cloudy = 0;
  for (int i = 0; i < 20000; ++i) {
    const glm::dvec3 q(ux(gen), ux(gen), uz(gen));
    const glm::dvec3 back(q.x - 0.4 * (q.z - 1000.0), q.y + 0.25 * (q.z - 1000.0), q.z);
    const float a = leaning.density(q), b = upright.density(back);
    ASSERT_EQ(a, b) << "at (" << q.x << ", " << q.y << ", " << q.z << ")";
    cloudy += a > 0.0f;
  }
  EXPECT_GT(cloudy, 200);
  // The lean grows the bounds by the slope times the height.
  EXPECT_GT(leaning.bounds().hi.x, upright.bounds().hi.x + 0.3 * (upright.bounds().hi.z - 1000.0));
}

TEST(CloudField, StretchDrawsFibresAlongItsDirectionWhateverTheWind) {
  // A layer of billow noise: with stretch 6 along x, density changes over a step along x
  // several times less than over the same step across (y). The wind blows along y: the fibres
  // follow stretch_direction, so a cloud keeps them when its drift is applied elsewhere.
  CloudParams p;
  Shape slab;
  slab.kind = ShapeKind::Slab;
  slab.center = {0.0, 0.0, 9000.0};
  slab.size = {5000.0, 5000.0, 300.0};
  p.shapes = {slab};
  p.coverage = 0.7;
  p.billow = 1.0;
  p.wind = {0.0, 20.0, 0.0};
  p.stretch_direction = {3.0, 0.0};  // normalised on use
  auto roughness_ratio = [&](double stretch) {
    CloudParams q = p;
    q.stretch = stretch;
    q.stretch_altitude = 8000.0;
    const CloudModel m(q, 20.0, 0.0);
    double along = 0.0, across = 0.0;
    std::mt19937_64 gen(2);
    std::uniform_real_distribution<double> u(-3000, 3000);
    for (int i = 0; i < 20000; ++i) {
      const glm::dvec3 a(u(gen), u(gen), 9000.0);
      along += std::fabs(m.density(a + glm::dvec3(60, 0, 0)) - m.density(a));
      across += std::fabs(m.density(a + glm::dvec3(0, 60, 0)) - m.density(a));
    }
    return across / along;
  };
  const double plain = roughness_ratio(1.0), fibred = roughness_ratio(6.0);
  std::printf("density change across / along the fibres: %.2f without stretch, %.2f with stretch 6\n", plain, fibred);
  EXPECT_NEAR(plain, 1.0, 0.15);
  EXPECT_GT(fibred, 3.0);
}

}  // namespace
}  // namespace nimbus::volume
