// Genus shapes, measured on the generated grids of several seeds each, with the
// measures of tests/support/cloud_shape.hpp:
//   - every single-cloud preset is one body: the largest 6-connected body holds at least 95 % of
//     the cloud voxels;
//   - cumulus (each preset, and each cloud of the cumulus field) has a flat base at the
//     condensation level: the interquartile range of the base height over the footprint's
//     interior is at most 5 % of the cloud's depth, or 2 voxels where that is larger;
//   - the cumulonimbus anvil spreads at the tropopause to at least 3 times the tower's width.
// Each test prints its figures, so that a preset can be retuned against the assertions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/vec2.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "support/cloud_shape.hpp"
#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/preset.hpp"

namespace nimbus::volume {
namespace {

constexpr double kExtinctionPerM = 0.04;  // render::CloudOptics' default sigma_t per unit density
const uint32_t kSeedOffsets[] = {0, 11, 23};

struct Measured {
  test::CloudMask mask;
  test::Bodies bodies;
  double voxel_m = 0;
};

Measured measure(const std::string& preset, uint32_t seed_offset, double field_size_m = 0) {
  const nlohmann::json doc = load_preset(preset);
  CloudParams p = cloud_from_json(doc.at("cloud"), preset);
  p.seed += seed_offset;
  if (p.field) {
    p.field->seed += seed_offset;
    if (field_size_m > 0) p.field->size_m = {field_size_m, field_size_m};
  }
  GenerateOptions o;
  o.voxel_size = doc.at("voxel_size").get<double>();
  const auto grid = generate_density(p, o);
  Measured m;
  m.mask = test::cloud_mask(*grid, kExtinctionPerM);
  m.bodies = test::cloud_bodies(m.mask);
  m.voxel_m = o.voxel_size;
  return m;
}

bool flat_enough(const test::BaseFlatness& b, double voxel_m) {
  return b.base_iqr_m <= std::max(0.05 * b.depth_m, 2.0 * voxel_m);
}

// The presets that are one cloud. Not: the fields and layers (many clouds, or a layer with
// breaks), cirrus fibratus ("detached clouds in the form of white, delicate filaments", WMO
// International Cloud Atlas: a patch of fibres), and steam and smoke (gases that break into
// puffs as they rise).
class SingleCloud : public ::testing::TestWithParam<std::string> {};

TEST_P(SingleCloud, IsOneBody) {
  for (uint32_t s : kSeedOffsets) {
    const Measured m = measure(GetParam(), s);
    std::printf("  [measured] %s seed +%u: %zu bodies, the largest holds %.1f %% of %zu cloud voxels\n",
                GetParam().c_str(), s, m.bodies.voxels.size(), 100 * m.bodies.largest_share(), m.bodies.total);
    EXPECT_GT(m.bodies.total, 1000u) << GetParam() << " seed +" << s;
    EXPECT_GE(m.bodies.largest_share(), 0.95) << GetParam() << " seed +" << s;
  }
}

INSTANTIATE_TEST_SUITE_P(Presets, SingleCloud,
                         ::testing::Values("cumulus-humilis", "cumulus-mediocris", "cumulus-congestus",
                                           "cumulonimbus-capillatus-incus", "altocumulus-lenticularis"),
                         [](const auto& info) {
                           std::string n = info.param;
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

class Cumulus : public ::testing::TestWithParam<std::string> {};

TEST_P(Cumulus, HasAFlatBase) {
  for (uint32_t s : kSeedOffsets) {
    const Measured m = measure(GetParam(), s);
    const test::BaseFlatness b = test::base_flatness(m.mask, m.bodies, 0);
    std::printf("  [measured] %s seed +%u: base IQR %.0f m over %zu of %zu columns, depth %.0f m (%.1f %%)\n",
                GetParam().c_str(), s, b.base_iqr_m, b.interior_columns, b.footprint_columns, b.depth_m,
                100 * b.base_iqr_m / b.depth_m);
    EXPECT_GT(b.interior_columns, 50u) << GetParam() << " seed +" << s;
    EXPECT_TRUE(flat_enough(b, m.voxel_m)) << GetParam() << " seed +" << s << ": base IQR " << b.base_iqr_m
                                           << " m, depth " << b.depth_m << " m";
  }
}

INSTANTIATE_TEST_SUITE_P(Presets, Cumulus,
                         ::testing::Values("cumulus-humilis", "cumulus-mediocris", "cumulus-congestus"),
                         [](const auto& info) {
                           std::string n = info.param;
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

// A cloud of the field stands on the condensation level: its lowest voxel is within two voxels
// of the field's lowest. Bodies wholly aloft are fragments the noise cut off a turret; they are
// counted, and must stay a small share of the field's cloud.
TEST(CumulusField, EveryCloudHasAFlatBase) {
  for (uint32_t s : {0u, 11u}) {
    const Measured m = measure("cumulus-field", s, 5000.0);
    std::vector<test::BaseFlatness> bases;
    int field_base = m.mask.nz;
    for (size_t body = 0; body < m.bodies.voxels.size(); ++body) {
      bases.push_back(test::base_flatness(m.mask, m.bodies, int32_t(body)));
      field_base = std::min(field_base, bases.back().lowest_layer);
    }
    // The field is periodic (one period generated): a cloud crossing the grid's side faces is cut
    // there, the rest of it lying across the opposite face, and the piece may be a sliver of its
    // rim, where the base curves up. Such pieces are not whole clouds; they are left out.
    std::vector<uint8_t> cut(bases.size(), 0);
    for (int k = 0; k < m.mask.nz; ++k)
      for (int j = 0; j < m.mask.ny; ++j)
        for (int i = 0; i < m.mask.nx; ++i)
          if (i == 0 || j == 0 || i == m.mask.nx - 1 || j == m.mask.ny - 1) {
            const int32_t l = m.bodies.label[m.mask.index(i, j, k)];
            if (l >= 0) cut[size_t(l)] = 1;
          }
    size_t measured = 0, aloft_voxels = 0;
    double worst = 0;
    for (size_t body = 0; body < bases.size(); ++body) {
      const test::BaseFlatness& b = bases[body];
      if (b.lowest_layer > field_base + 2) {
        aloft_voxels += m.bodies.voxels[body];
        continue;
      }
      if (cut[body]) continue;
      if (b.interior_columns < 9) continue;  // too small for a base to be measured
      ++measured;
      worst = std::max(worst, b.base_iqr_m / std::max(0.05 * b.depth_m, 2.0 * m.voxel_m));
      EXPECT_TRUE(flat_enough(b, m.voxel_m)) << "field seed +" << s << " cloud " << body << " (" << b.interior_columns
                                             << " of " << b.footprint_columns << " columns): base IQR " << b.base_iqr_m
                                             << " m, depth " << b.depth_m << " m";
    }
    const double aloft = double(aloft_voxels) / double(m.bodies.total);
    std::printf("  [measured] cumulus-field seed +%u: %zu clouds measured, worst base IQR / allowance %.2f; fragments "
                "aloft hold %.2f %% of the cloud\n", s, measured, worst, 100 * aloft);
    EXPECT_GE(measured, 20u);
    EXPECT_LE(aloft, 0.05);
  }
}

TEST(Cumulonimbus, AnvilSpreadsToThreeTowerWidths) {
  for (uint32_t s : kSeedOffsets) {
    const Measured m = measure("cumulonimbus-capillatus-incus", s);
    const test::TowerAndAnvil t = test::tower_and_anvil(m.mask, m.bodies, 0);
    std::printf("  [measured] cumulonimbus seed +%u: tower %.0f m, anvil %.0f m wide: %.2f\n", s, t.tower_width_m,
                t.anvil_width_m, t.ratio());
    EXPECT_GE(t.ratio(), 3.0) << "seed +" << s;
  }
}

// Cirrus fall streaks: along the wind, the ice falls (the density-weighted altitude drops from
// the upwind third to the downwind one), the trail curves (it falls steeply below the heads and
// levels out downwind: the first drop exceeds the second), and it thins (less ice per voxel
// downwind). Every voxel with density counts: cirrus is mostly thinner than the cloud mask.
TEST(Cirrus, FibresFallCurveAndThinDownwind) {
  for (uint32_t s : kSeedOffsets) {
    const nlohmann::json doc = load_preset("cirrus-fibratus");
    CloudParams p = cloud_from_json(doc.at("cloud"), "cirrus-fibratus");
    p.seed += s;
    GenerateOptions o;
    o.voxel_size = doc.at("voxel_size").get<double>();
    const auto grid = generate_density(p, o);
    const glm::dvec2 wind = glm::dvec2(p.stretch_direction) / std::hypot(p.stretch_direction.x, p.stretch_direction.y);
    struct V { double along, z, d; };
    std::vector<V> vs;
    for (auto v = grid->cbeginValueOn(); v; ++v) {
      if (!(*v > 1e-3f)) continue;
      const openvdb::Vec3d w = grid->indexToWorld(v.getCoord());
      vs.push_back({w.x() * wind.x + w.y() * wind.y, w.z(), double(*v)});
    }
    ASSERT_GT(vs.size(), 1000u);
    double lo = 1e300, hi = -1e300;
    for (const V& v : vs) lo = std::min(lo, v.along), hi = std::max(hi, v.along);
    double mass[3] = {0, 0, 0}, zsum[3] = {0, 0, 0}, count[3] = {0, 0, 0};
    for (const V& v : vs) {
      const int third = std::min(2, int(3.0 * (v.along - lo) / (hi - lo)));
      mass[third] += v.d, zsum[third] += v.d * v.z, count[third] += 1;
    }
    double z[3], per_voxel[3];
    for (int t = 0; t < 3; ++t) z[t] = zsum[t] / mass[t], per_voxel[t] = mass[t] / count[t];
    std::printf("  [measured] cirrus-fibratus seed +%u: altitude by third along the wind %.0f, %.0f, %.0f m; density per "
                "voxel %.3f, %.3f, %.3f\n", s, z[0], z[1], z[2], per_voxel[0], per_voxel[1], per_voxel[2]);
    EXPECT_GE(z[0] - z[2], 300.0) << "seed +" << s << ": the streaks do not fall";
    EXPECT_GT(z[0] - z[1], 1.2 * (z[1] - z[2])) << "seed +" << s << ": the streaks do not curve";
    EXPECT_LT(per_voxel[2], 0.8 * per_voxel[0]) << "seed +" << s << ": the streaks do not thin";
  }
}

}  // namespace
}  // namespace nimbus::volume
