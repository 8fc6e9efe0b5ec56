// The size factor (volume/cloud_scale.hpp): every preset made f times as large about its base
// centre keeps its base, grows its box by f, keeps its shape statistics, and scales back exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "nimbus/volume/cloud_scale.hpp"
#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/preset.hpp"

namespace nimbus::volume {
namespace {

CloudParams preset_params(const std::string& name) { return cloud_from_json(load_preset(name).at("cloud"), name); }

TEST(CloudScale, RefusesFactorsOutsideItsRangeByName) {
  for (const double f : {0.0, -1.0, 0.005, 101.0, std::numeric_limits<double>::quiet_NaN(),
                         std::numeric_limits<double>::infinity()}) {
    try {
      check_size_factor(f, "--size");
      ADD_FAILURE() << f << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--size: must be within [0.01, 100], got ", 0), 0u) << e.what();
    }
  }
  EXPECT_NO_THROW(check_size_factor(0.01, "size"));
  EXPECT_NO_THROW(check_size_factor(100.0, "size"));
  EXPECT_THROW(scale_cloud(preset_params("cumulus-humilis"), 0.0), std::invalid_argument);
}

// The model's box (shapes, displacement and ceiling, before any noise) grows by f about the base
// centre, which stays where it was (a field's across only); lengths grow and frequencies shrink by
// f; f then 1/f is the cloud again. Every preset, fields included.
TEST(CloudScale, EveryPresetsBoxGrowsAboutItsBaseCentre) {
  for (const PresetInfo& info : list_presets()) {
    const CloudParams p = preset_params(info.name);
    for (const double f : {0.5, 2.0, 3.0}) {
      SCOPED_TRACE(info.name + " x" + std::to_string(f));
      const CloudParams q = scale_cloud(p, f);
      EXPECT_NO_THROW(validate(q));
      const glm::dvec3 base = base_centre(p), base_q = base_centre(q);
      for (int a = 0; a < 3; ++a) EXPECT_NEAR(base_q[a], base[a], 1e-9 * (1.0 + std::abs(base[a])));
      const Aabb b = CloudModel(p, 10.0, 0.0).bounds(), bq = CloudModel(q, 10.0 * f, 0.0).bounds();
      // A field's clouds keep their species' depth rule (a mediocris stays under 1 km deep): its
      // layout scales across, not its depth.
      for (int a = 0; a < (p.field ? 2 : 3); ++a) {
        const double tol = 1e-6 * (1.0 + std::abs(b.hi[a] - b.lo[a])) * f;
        EXPECT_NEAR(bq.lo[a], base[a] + f * (b.lo[a] - base[a]), tol) << "axis " << a;
        EXPECT_NEAR(bq.hi[a], base[a] + f * (b.hi[a] - base[a]), tol) << "axis " << a;
      }
      EXPECT_DOUBLE_EQ(q.frequency, p.frequency / f);
      EXPECT_DOUBLE_EQ(q.erosion_frequency, p.erosion_frequency / f);
      EXPECT_DOUBLE_EQ(q.displacement, p.displacement * f);
      EXPECT_DOUBLE_EQ(q.base_softness, p.base_softness * f);
      EXPECT_EQ(q.base_altitude, p.base_altitude);  // the base stays at the condensation level
      EXPECT_EQ(q.coverage, p.coverage);
      EXPECT_EQ(q.seed, p.seed);
      EXPECT_EQ(q.wind, p.wind);
      const CloudParams back = scale_cloud(q, 1.0 / f);
      EXPECT_NEAR(back.frequency, p.frequency, 1e-15 * p.frequency);
      for (std::size_t i = 0; i < p.shapes.size(); ++i)
        for (int a = 0; a < 3; ++a) {
          EXPECT_NEAR(back.shapes[i].center[a], p.shapes[i].center[a], 1e-9 * (1.0 + std::abs(p.shapes[i].center[a])));
          EXPECT_NEAR(back.shapes[i].size[a], p.shapes[i].size[a], 1e-9 * p.shapes[i].size[a]);
        }
    }
  }
}

// The same cloud at another size: generated at f times the voxel size, the scaled cumulus fills
// about as many voxels (its noise is the same noise, moved: the shapes scale about the base, the
// lattice about the origin), so its cover and depth in voxels stay.
TEST(CloudScale, AScaledCumulusAtAScaledVoxelFillsAsManyVoxels) {
  const CloudParams p = preset_params("cumulus-mediocris");
  GenerateOptions opt;
  opt.voxel_size = 40.0;
  GenerateStats s1, s2;
  (void)generate_density(p, opt, &s1);
  for (const double f : {0.5, 2.0}) {
    GenerateOptions o2 = opt;
    o2.voxel_size = opt.voxel_size * f;
    (void)generate_density(scale_cloud(p, f), o2, &s2);
    const double ratio = double(s2.active_voxels) / double(s1.active_voxels);
    std::printf("cumulus-mediocris x%g at %g m voxels: %lld active voxels, %lld at x1 (ratio %.3f)\n", f,
                o2.voxel_size, (long long)s2.active_voxels, (long long)s1.active_voxels, ratio);
    EXPECT_GT(ratio, 0.85);
    EXPECT_LT(ratio, 1.15);
  }
}

}  // namespace
}  // namespace nimbus::volume
