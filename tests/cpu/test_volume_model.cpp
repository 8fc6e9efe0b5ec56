// The density model: Ebert's gas function against its formula, shape coverage, the cloud
// field's invariants, and sparse generation against the naive every-voxel anchor.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <numbers>
#include <random>

#include "nimbus/volume/cloud_model.hpp"
#include "nimbus/volume/gas.hpp"
#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/shape.hpp"

namespace nimbus::volume {
namespace {

TEST(VolumeGas, MatchesEbertsFormula) {
  for (float turb : {0.001f, 0.1f, 0.37f, 0.5f, 0.9f, 1.0f, 1.7f})
    for (float md : {0.25f, 1.0f, 3.0f, 5.7f})
      for (float e : {0.3f, 1.0f, 2.0f, 5.0f}) {
        const double ref = std::pow(double(turb) * md, double(e));
        EXPECT_NEAR(gas_density(turb, {md, e, false}), ref, 1e-6 * std::max(1.0, ref)) << turb << " " << md << " " << e;
        const double s = 0.5 * (1.0 + std::sin(double(turb) * std::numbers::pi));
        const double ref_sine = std::pow(s * md, double(e));
        EXPECT_NEAR(gas_density(turb, {md, e, true}), ref_sine, 2e-6 * std::max(1.0, ref_sine));
      }
}

TEST(VolumeGas, NonPositiveOrNaNInputGivesZeroAndOutputIsAlwaysFinite) {
  EXPECT_EQ(gas_density(0.0f, {}), 0.0f);
  EXPECT_EQ(gas_density(-0.5f, {2.0f, 0.5f, false}), 0.0f);  // pow of a negative would be NaN
  EXPECT_EQ(gas_density(std::numeric_limits<float>::quiet_NaN(), {}), 0.0f);
  const float huge = gas_density(1e30f, {1e30f, 16.0f, false});
  EXPECT_TRUE(std::isfinite(huge));
  EXPECT_GE(huge, 0.0f);
}

Shape make(ShapeKind k) {
  Shape s;
  s.kind = k;
  s.center = {10, -20, 300};
  s.size = {200, 150, 100};
  s.end = {400, 50, 350};
  s.falloff = 0.4;
  s.weight = 0.8;
  return s;
}

TEST(VolumeShape, CoverageIsWeightInsideZeroOutsideAndWithinBounds) {
  std::mt19937_64 rng(7);
  for (ShapeKind k : {ShapeKind::Ellipsoid, ShapeKind::Capsule, ShapeKind::Slab, ShapeKind::Lens}) {
    const Shape s = make(k);
    EXPECT_DOUBLE_EQ(shape_coverage(s, s.center), s.weight) << int(k);
    const Aabb b = shape_bounds(s);
    const Aabb wide = b.expanded(300);
    std::uniform_real_distribution<double> ux(wide.lo.x, wide.hi.x), uy(wide.lo.y, wide.hi.y), uz(wide.lo.z, wide.hi.z);
    int inside = 0;
    for (int i = 0; i < 200000; ++i) {
      const glm::dvec3 p(ux(rng), uy(rng), uz(rng));
      const double c = shape_coverage(s, p);
      ASSERT_GE(c, 0.0);
      ASSERT_LE(c, s.weight);
      const bool in_box = p.x >= b.lo.x && p.x <= b.hi.x && p.y >= b.lo.y && p.y <= b.hi.y && p.z >= b.lo.z && p.z <= b.hi.z;
      if (c > 0.0) {
        ASSERT_TRUE(in_box) << "kind " << int(k) << " coverage outside its bounds";
      }
      inside += c > 0.0;
    }
    EXPECT_GT(inside, 100) << int(k);
  }
}

TEST(VolumeShape, CoverageFallsMonotonicallyAndContinuouslyToTheBoundary) {
  for (ShapeKind k : {ShapeKind::Ellipsoid, ShapeKind::Slab, ShapeKind::Lens}) {
    const Shape s = make(k);
    const glm::dvec3 dir = glm::normalize(glm::dvec3(0.6, 0.3, 0.2));
    double prev = shape_coverage(s, s.center), max_step = 0.0;
    for (int i = 1; i <= 4000; ++i) {
      const double c = shape_coverage(s, s.center + dir * (0.1 * i));
      EXPECT_LE(c, prev + 1e-12) << int(k) << " at step " << i;
      max_step = std::max(max_step, prev - c);
      prev = c;
    }
    EXPECT_EQ(prev, 0.0);
    EXPECT_LT(max_step, 0.01) << "coverage jumps (not a fuzzy boundary), kind " << int(k);
  }
}

CloudParams test_cloud() {
  CloudParams p;
  Shape body;
  body.center = {0, 0, 1200};
  body.size = {700, 600, 450};
  body.falloff = 0.5;
  Shape tower = body;
  tower.center = {150, 80, 1600};
  tower.size = {350, 320, 420};
  p.shapes = {body, tower};
  p.coverage = 0.55;
  p.billow = 0.4;
  p.erosion = 0.2;
  p.displacement = 60;
  p.gas = {1.5f, 1.3f, false};
  p.seed = 11;
  return p;
}

TEST(VolumeModel, DensityIsFiniteNonNegativeAndZeroOutsideTheBounds) {
  CloudParams p = test_cloud();
  p.wind = {12, -3, 0};
  p.evolution = 0.05;
  const CloudModel m(p, 20.0, 30.0);
  const Aabb b = m.bounds();
  std::mt19937_64 rng(3);
  const Aabb wide = b.expanded(800);
  std::uniform_real_distribution<double> ux(wide.lo.x, wide.hi.x), uy(wide.lo.y, wide.hi.y), uz(wide.lo.z, wide.hi.z);
  int positive = 0;
  for (int i = 0; i < 200000; ++i) {
    const glm::dvec3 q(ux(rng), uy(rng), uz(rng));
    const float d = m.density(q);
    ASSERT_TRUE(std::isfinite(d));
    ASSERT_GE(d, 0.0f);
    const bool in_box = q.x >= b.lo.x && q.x <= b.hi.x && q.y >= b.lo.y && q.y <= b.hi.y && q.z >= b.lo.z && q.z <= b.hi.z;
    if (d > 0.0f) {
      ASSERT_TRUE(in_box);
    }
    positive += d > 0.0f;
  }
  EXPECT_GT(positive, 1000);
}

TEST(VolumeModel, BatchedDensitiesEqualTheScalarPathBitForBit) {
  const CloudModel m(test_cloud(), 15.0, 0.0);
  std::vector<glm::dvec3> pts;
  for (int i = 0; i < 20000; ++i) pts.push_back({-800 + 0.083 * i, 37.0 - 0.01 * i, 900 + 0.041 * i});
  std::vector<float> batch(pts.size());
  const int64_t evaluated = m.densities(pts.data(), pts.size(), batch.data());
  int64_t useful = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    ASSERT_EQ(batch[i], m.density(pts[i])) << i;
  }
  for (float d : batch) useful += d > 0.0f;
  EXPECT_GE(evaluated, useful);  // every positive density needed the noise
  EXPECT_LT(evaluated, int64_t(pts.size()));  // and points far from the shapes did not
}

TEST(VolumeModel, BadParametersNameTheParameter) {
  auto expect_throw = [](CloudParams p, const char* word) {
    try {
      validate(p);
      ADD_FAILURE() << "no error for " << word;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
  };
  CloudParams p = test_cloud();
  auto q = p; q.shapes.clear(); expect_throw(q, "shapes");
  q = p; q.shapes[1].size.z = 0; expect_throw(q, "shapes[1].size");
  q = p; q.coverage = 1.5; expect_throw(q, "coverage");
  q = p; q.frequency = std::nan(""); expect_throw(q, "frequency");
  q = p; q.gas.exponent = 0; expect_throw(q, "exponent");
  q = p; q.erosion = -0.1; expect_throw(q, "erosion");
  q = p; q.wind.x = INFINITY; expect_throw(q, "wind");
  q = p; q.octaves = 0; expect_throw(q, "octaves");
  q = p; q.furrows = 1.5; expect_throw(q, "furrows");
  q = p; q.furrow_frequency = 0; expect_throw(q, "furrow_frequency");
}

bool same_grids(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b) {
  if (a.activeVoxelCount() != b.activeVoxelCount()) return false;
  auto acc = b.getConstAccessor();
  for (auto it = a.cbeginValueOn(); it; ++it) {
    float v;
    if (!acc.probeValue(it.getCoord(), v) || v != *it) return false;
  }
  return true;
}

TEST(VolumeGenerate, SparseGridEqualsTheNaiveEveryVoxelAnchorAndSkipsWork) {
  const CloudParams p = test_cloud();
  GenerateOptions o;
  o.voxel_size = 40.0;
  GenerateStats sparse_stats, naive_stats;
  const auto sparse = generate_density(p, o, &sparse_stats);
  o.sparse = false;
  const auto naive = generate_density(p, o, &naive_stats);
  EXPECT_TRUE(same_grids(*sparse, *naive));
  EXPECT_GT(sparse_stats.active_voxels, 1000);
  EXPECT_EQ(sparse_stats.active_voxels, int64_t(sparse->activeVoxelCount()));
  EXPECT_LT(sparse_stats.noise_evaluations, naive_stats.noise_evaluations);
  EXPECT_LE(sparse_stats.voxels_visited, naive_stats.voxels_visited);
  // Every active voxel holds a positive, finite density; the grid is a fog volume named density.
  for (auto it = sparse->cbeginValueOn(); it; ++it) {
    ASSERT_GE(*it, kMinDensity);
    ASSERT_TRUE(std::isfinite(*it));
  }
  EXPECT_EQ(sparse->getName(), "density");
  EXPECT_EQ(sparse->getGridClass(), openvdb::GRID_FOG_VOLUME);
  EXPECT_EQ(sparse->background(), 0.0f);
  EXPECT_DOUBLE_EQ(sparse->voxelSize()[0], 40.0);
}

TEST(VolumeGenerate, SameParametersSameGridOtherSeedOtherGrid) {
  const CloudParams p = test_cloud();
  GenerateOptions o;
  o.voxel_size = 50.0;
  EXPECT_TRUE(same_grids(*generate_density(p, o), *generate_density(p, o)));
  CloudParams q = p;
  q.seed = 12;
  EXPECT_FALSE(same_grids(*generate_density(p, o), *generate_density(q, o)));
}

TEST(VolumeGenerate, WindTranslatesTheCloudExactly) {
  // Without evolution or displacement, time only moves the cloud: by 2 voxels here.
  CloudParams p = test_cloud();
  p.displacement = 0.0;
  p.wind = {25.0, -12.5, 0.0};
  GenerateOptions o;
  o.voxel_size = 25.0;
  const auto g0 = generate_density(p, o);
  o.time = 2.0;  // moves by (50, -25, 0) m = (2, -1, 0) voxels
  const auto g2 = generate_density(p, o);
  ASSERT_EQ(g0->activeVoxelCount(), g2->activeVoxelCount());
  auto acc = g2->getConstAccessor();
  for (auto it = g0->cbeginValueOn(); it; ++it) {
    const openvdb::Coord c = it.getCoord() + openvdb::Coord(2, -1, 0);
    ASSERT_FLOAT_EQ(acc.getValue(c), *it) << c;
  }
}

TEST(VolumeGenerate, EvolutionIsContinuousInTimeNoPopping) {
  CloudParams p = test_cloud();
  p.evolution = 0.02;
  p.wind = {5, 0, 0};
  const CloudModel a(p, 20.0, 10.0), b(p, 20.0, 10.05), c(p, 20.0, 10.1);
  double dab = 0, dac = 0;
  int n = 0;
  for (int i = 0; i < 40000; ++i) {
    const glm::dvec3 q(-600 + 0.031 * i, -200 + 0.011 * i, 900 + 0.017 * i);
    dab += std::fabs(a.density(q) - b.density(q));
    dac += std::fabs(a.density(q) - c.density(q));
    n += a.density(q) > 0;
  }
  ASSERT_GT(n, 1000);
  EXPECT_GT(dac, 0.0);
  // Halving the time step roughly halves the change (a smooth field, no jumps).
  EXPECT_NEAR(dab / dac, 0.5, 0.15);
}

TEST(VolumeGenerate, OctavesStopAtTheVoxelFootprint) {
  CloudParams p = test_cloud();
  p.octaves = 12;
  GenerateOptions o;
  o.voxel_size = 50.0;  // Nyquist 0.01 cycles/m; gradient octave i tops at 2^i / 400
  GenerateStats s;
  generate_density(p, o, &s);
  EXPECT_EQ(s.octaves_requested, 12);
  EXPECT_EQ(s.octaves_used, 3);  // 1/400, 2/400, 4/400 <= 0.01 < 8/400
}

TEST(VolumeGenerate, BoundsBeyondMemoryAreRefusedBeforeAllocating) {
  CloudParams p = test_cloud();
  p.shapes[0].size = {4e5, 4e5, 4e4};
  GenerateOptions o;
  o.voxel_size = 1.0;
  EXPECT_THROW(generate_density(p, o), std::invalid_argument);
}

// Furrows (ridged noise subtracted, the cumulonimbus's deep grooves): the batched path still
// equals the scalar path bit for bit, the furrows only ever remove density (so the bound that
// skips the noise still holds), they cut a real share of the cloud away, and furrows = 0 is
// the plain field.
TEST(VolumeModel, FurrowsOnlyCarveAndKeepBatchedEqualToScalar) {
  CloudParams plain = test_cloud();
  CloudParams furrowed = plain;
  furrowed.furrows = 0.6;
  furrowed.furrow_frequency = 1.0 / 700.0;
  const CloudModel a(plain, 15.0, 0.0), b(furrowed, 15.0, 0.0);
  std::vector<glm::dvec3> pts;
  for (int i = 0; i < 20000; ++i) pts.push_back({-800 + 0.083 * i, 37.0 - 0.01 * i, 900 + 0.041 * i});
  std::vector<float> batch(pts.size());
  b.densities(pts.data(), pts.size(), batch.data());
  int carved = 0, inside = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    ASSERT_EQ(batch[i], b.density(pts[i])) << i;
    const float da = a.density(pts[i]);
    ASSERT_LE(batch[i], da) << i;
    inside += da > 0.0f;
    carved += da > 0.0f && batch[i] == 0.0f;
  }
  ASSERT_GT(inside, 1000);
  EXPECT_GT(carved, inside / 20) << "the furrows cut into the cloud";
  EXPECT_LT(carved, inside) << "and leave lumps between them";
  CloudParams zero = furrowed;
  zero.furrows = 0.0;
  const CloudModel z(zero, 15.0, 0.0);
  for (size_t i = 0; i < pts.size(); i += 7) ASSERT_EQ(z.density(pts[i]), a.density(pts[i]));
  GenerateOptions o;
  o.voxel_size = 40.0;
  const auto sparse = generate_density(furrowed, o);
  o.sparse = false;
  EXPECT_TRUE(same_grids(*sparse, *generate_density(furrowed, o)));
}

}  // namespace
}  // namespace nimbus::volume

namespace nimbus::volume {
namespace {

TEST(VolumeGenerate, TemperatureCoolsWithHeightOnTheDensityVoxels) {
  CloudParams p = test_cloud();
  p.temperature_base = 900.0;
  p.temperature_height = 1200.0;
  GenerateOptions o;
  o.voxel_size = 50.0;
  const auto d = generate_density(p, o);
  const auto t = generate_temperature(p, *d);
  ASSERT_TRUE(t);
  EXPECT_EQ(t->getName(), "temperature");
  EXPECT_TRUE(t->tree().hasSameTopology(d->tree()));
  EXPECT_EQ(t->transform(), d->transform());
  for (auto it = t->cbeginValueOn(); it; ++it) {
    const double z = t->indexToWorld(it.getCoord()).z();
    ASSERT_NEAR(*it, std::clamp(1.0 - (z - 900.0) / 1200.0, 0.0, 1.0), 1e-6);
  }
  p.temperature_height = 0.0;
  EXPECT_FALSE(generate_temperature(p, *d));
}

}  // namespace
}  // namespace nimbus::volume
