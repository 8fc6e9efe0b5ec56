// Periodic fields (a sky without edges): the density at p equals the density at
// p + (period, 0, 0) and p + (0, period, 0), the generated grid spans exactly one period, its
// faces continue into the next period, and the layout never stacks clouds across an edge.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/common.hpp>
#include <cstdio>
#include <random>

#include "nimbus/volume/cloud_field.hpp"
#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/preset.hpp"

namespace nimbus::volume {
namespace {

CloudParams preset_params(const std::string& name) {
  return cloud_from_json(load_preset(name).at("cloud"), name);
}

// A smaller cumulus field than the preset's, for speed: 4 x 4 km.
CloudParams small_cumulus_field() {
  CloudParams p = preset_params("cumulus-field");
  p.field->size_m = {4000.0, 4000.0};
  p.field->max_diameter_m = 1200.0;
  return p;
}

bool close(float a, float b) {
  return std::fabs(a - b) <= 1e-5f * std::max(std::fabs(a), std::fabs(b)) + 1e-7f;
}

// Density at random points of the tile (where the model holds cloud) against the same points a
// period away in x, in y and in both, through the scalar and the batched paths.
void expect_periodic(const CloudParams& p, double voxel, double time, const char* what) {
  const CloudModel m(p, voxel, time);
  ASSERT_TRUE(m.tile().has_value()) << what;
  const glm::dvec2 P = m.tile()->size_m, lo = m.tile()->lo_m;
  const Aabb b = m.bounds();
  EXPECT_DOUBLE_EQ(b.lo.x, lo.x);
  EXPECT_DOUBLE_EQ(b.hi.x - b.lo.x, P.x);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> ux(lo.x, lo.x + P.x), uy(lo.y, lo.y + P.y), uz(b.lo.z, b.hi.z);
  int cloudy = 0, tested = 0;
  std::vector<glm::dvec3> pts;
  for (int i = 0; i < 200000 && cloudy < 400; ++i) {
    const glm::dvec3 x(ux(rng), uy(rng), uz(rng));
    const float d = m.density(x);
    // Near the tile's edges and in its middle alike; most points are clear air.
    if (d <= 0.0f && (i % 50) != 0) continue;
    cloudy += d > 0.0f;
    ++tested;
    for (const glm::dvec3 o : {glm::dvec3(P.x, 0, 0), glm::dvec3(0, P.y, 0), glm::dvec3(-P.x, P.y, 0), glm::dvec3(2 * P.x, 0, 0)})
      ASSERT_TRUE(close(d, m.density(x + o))) << what << " at (" << x.x << ", " << x.y << ", " << x.z << ") + (" << o.x
                                              << ", " << o.y << "): " << d << " vs " << m.density(x + o);
    pts.push_back(x);
    pts.push_back(x + glm::dvec3(0, -P.y, 0));
  }
  EXPECT_GE(cloudy, 100) << what << ": too few cloudy points to test";
  std::vector<float> batch(pts.size());
  m.densities(pts.data(), pts.size(), batch.data());
  for (size_t i = 0; i < pts.size(); i += 2) ASSERT_TRUE(close(batch[i], batch[i + 1])) << what << " (batched) point " << i / 2;
  std::printf("  [measured] %s, t = %g s: %d cloudy of %d points equal a period away\n", what, time, cloudy, tested);
}

TEST(PeriodicField, DensityRepeatsWithThePeriodAtAnyTime) {
  expect_periodic(small_cumulus_field(), 20.0, 0.0, "cumulus field 4 km");
  expect_periodic(small_cumulus_field(), 20.0, 95.0, "cumulus field 4 km");  // wind 6 m/s: 570 m on, and evolved
  expect_periodic(preset_params("stratocumulus-field"), 25.0, 0.0, "stratocumulus-field");
  expect_periodic(preset_params("stratocumulus-field"), 25.0, 400.0, "stratocumulus-field");
}

TEST(PeriodicField, TheGridSpansOnePeriodAndItsFacesContinueIntoTheNext) {
  for (const char* name : {"cumulus", "stratocumulus-field"}) {
    const bool cu = std::string(name) == "cumulus";
    const CloudParams p = cu ? small_cumulus_field() : preset_params("stratocumulus-field");
    const double vs = cu ? 20.0 : 50.0;
    GenerateOptions o;
    o.voxel_size = vs;
    o.time = 30.0;
    const auto grid = generate_density(p, o);
    const openvdb::CoordBBox box = density_index_box(p, vs, o.time);
    const CloudModel m(p, vs, o.time);
    const glm::dvec2 P = m.tile()->size_m;
    const int nx = int(std::lround(P.x / vs)), ny = int(std::lround(P.y / vs));
    ASSERT_EQ(box.dim().x(), nx) << name;
    ASSERT_EQ(box.dim().y(), ny) << name;
    EXPECT_TRUE(box.isInside(grid->evalActiveVoxelBoundingBox())) << name << ": " << box << " holds not "
                                                                 << grid->evalActiveVoxelBoundingBox();
    // The first face's voxels against the model one period on, and the last face's against the
    // model one period back: the grid continues seamlessly into its neighbours.
    auto acc = grid->getConstAccessor();
    int nonzero = 0, compared = 0;
    for (int axis = 0; axis < 2; ++axis)
      for (int a = 0; a < (axis == 0 ? ny : nx); ++a)
        for (int k = box.min().z(); k <= box.max().z(); ++k) {
          openvdb::Coord c0 = box.min(), c1 = box.min();
          c0[2] = c1[2] = k;
          c0[1 - axis] = c1[1 - axis] = box.min()[1 - axis] + a;
          c1[axis] = box.max()[axis];
          for (const auto& [c, step] : {std::pair{c0, 1.0}, std::pair{c1, -1.0}}) {
            glm::dvec3 w(c.x() * vs, c.y() * vs, c.z() * vs);
            w[axis] += step * P[axis];
            const float v = acc.getValue(c), expect = m.density(w);
            const float e = expect >= kMinDensity ? expect : 0.0f;
            ASSERT_TRUE(close(v, e)) << name << " voxel " << c << ": " << v << ", a period away " << e;
            nonzero += v > 0;
            ++compared;
          }
        }
    std::printf("  [measured] %s: %d x %d voxels (one period), %d of %d face voxels hold cloud\n", name, nx, ny, nonzero,
                compared);
    EXPECT_GT(nonzero, 20) << name << ": the faces hold too little cloud for the test to mean anything";
  }
}

TEST(PeriodicField, TheLayoutWrapsAndNeverStacksAcrossAnEdge) {
  CloudFieldParams f;
  f.size_m = {10000.0, 10000.0};
  f.coverage = 0.38;
  f.seed = 21;
  f.periodic = true;
  const std::vector<FieldCloud> a = field_layout(f);
  ASSERT_GT(a.size(), 500u);
  int near_edge = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    near_edge += std::fabs(a[i].center_m.x) + 0.5 * a[i].diameter_m > 5000.0;
    for (size_t j = i + 1; j < a.size(); ++j) {
      glm::dvec2 d = a[i].center_m - a[j].center_m;
      d -= f.size_m * glm::round(d / f.size_m);  // the shortest way round
      const double r = 0.5 * (a[i].diameter_m + a[j].diameter_m);
      ASSERT_GE(d.x * d.x + d.y * d.y, r * r * (1 - 1e-12)) << "clouds " << i << " and " << j << " stack across an edge";
    }
  }
  EXPECT_GT(near_edge, 10) << "no cloud crosses the edge: the wrap is not tested";
  CloudFieldParams flat = f;
  flat.periodic = false;
  std::printf("  [measured] the preset's layout: %zu clouds periodic, %zu not; %d cross the x edges\n", a.size(),
              field_layout(flat).size(), near_edge);
}

TEST(PeriodicField, WhatCannotBePeriodicIsRefusedByName) {
  auto refused = [](CloudParams p, const char* word) {
    try {
      CloudModel m(p, 20.0, 0.0);
      ADD_FAILURE() << word << ": accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
  };
  CloudParams p = small_cumulus_field();
  p.stretch = 3.0;
  refused(p, "stretch");
  p = small_cumulus_field();
  p.noise = noise::Kind::Wavelet;
  refused(p, "wavelet");
  p = small_cumulus_field();
  p.lacunarity = 2.5;
  refused(p, "lacunarity");
  p = small_cumulus_field();
  p.field->max_diameter_m = 3800.0;  // a cloud nearly as wide as the 4 km period
  p.field->min_diameter_m = 3700.0;
  refused(p, "period");
  p = small_cumulus_field();
  p.period_m = {5000.0, 5000.0};  // not the field's size
  refused(p, "period");
}

}  // namespace
}  // namespace nimbus::volume
