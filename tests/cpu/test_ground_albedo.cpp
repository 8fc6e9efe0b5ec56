// The sky scene's ground albedo (render/scene/ground_albedo.hpp): its albedos lie where Oke's
// table puts fields, meadows and woods, it varies (a texture, not a colour), it tiles seamlessly,
// its mip chain is the box filter, and the footprint filter takes the variation out where a
// pixel covers kilometres (toward the horizon) while leaving it near the eye.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "nimbus/render/scene/ground_albedo.hpp"
#include "nimbus/render/scene/scene.hpp"

namespace nimbus::render {
namespace {

double luminance(const glm::dvec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

std::vector<double> level0_luminance(const GroundAlbedoTexture& t) {
  std::vector<double> l;
  for (const glm::vec3& c : t.levels[0]) l.push_back(luminance(glm::dvec3(c)));
  return l;
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * (v.size() - 1))];
}

TEST(GroundAlbedo, ItsAlbedosAreThoseOfFieldsMeadowsAndWoods) {
  const auto t = sky_ground_albedo();
  // Oke (1987) table 2.1: vegetation and soils 0.05-0.26; the mean a green-brown 0.1-0.2.
  EXPECT_GT(t->mean_luminance, 0.10);
  EXPECT_LT(t->mean_luminance, 0.20);
  EXPECT_GT(t->mean.y, t->mean.z);  // green over blue: vegetation, not grey
  EXPECT_GT(t->mean.x, t->mean.z);  // and some brown
  const std::vector<double> l = level0_luminance(*t);
  EXPECT_GE(quantile(l, 0.01), 0.03);
  EXPECT_LE(quantile(l, 0.99), 0.30);
  for (const glm::vec3& c : t->levels[0])
    for (int k = 0; k < 3; ++k) ASSERT_TRUE(c[k] >= 0.0f && c[k] <= 1.0f);
  // A texture: the middle 90 % of its texels span more than a quarter of the mean.
  EXPECT_GT(quantile(l, 0.95) - quantile(l, 0.05), 0.25 * t->mean_luminance);
}

// Across the wrap (last column to the first, last row to the first) neighbouring texels differ no
// more than neighbours inside do: no seam where the texture repeats.
TEST(GroundAlbedo, ItTilesSeamlessly) {
  const auto t = sky_ground_albedo();
  const int n = t->size(0);
  const auto at = [&](int i, int j) { return luminance(glm::dvec3(t->levels[0][static_cast<std::size_t>(j) * n + i])); };
  double inside = 0.0, seam = 0.0, seam_max = 0.0, inside_max = 0.0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const double d = std::abs(at(i + 1, j) - at(i, j)) + std::abs(at(j, i + 1) - at(j, i));
      inside += d;
      inside_max = std::max(inside_max, d);
    }
    const double d = std::abs(at(0, j) - at(n - 1, j)) + std::abs(at(j, 0) - at(j, n - 1));
    seam += d;
    seam_max = std::max(seam_max, d);
  }
  inside /= static_cast<double>(n) * (n - 1);
  seam /= n;
  EXPECT_LT(seam, 1.5 * inside) << "mean step across the seam " << seam << ", inside " << inside;
  EXPECT_LE(seam_max, inside_max);
  // And the read repeats with the period: uv and uv + 1 are the same texels.
  for (double u : {0.013, 0.5, 0.987})
    for (double lod : {0.0, 2.5})
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(sample_ground_texture(*t, {u, 0.3}, lod)[k], sample_ground_texture(*t, {u + 1.0, 0.3 - 1.0}, lod)[k], 1e-6);
}

TEST(GroundAlbedo, EachMipLevelIsTheBoxMeanOfTheOneBelow) {
  const auto t = sky_ground_albedo();
  ASSERT_EQ(t->size(t->level_count() - 1), 1);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(t->levels.back()[0][k], t->mean[k], 1e-5);
  const int n = t->size(3);
  const auto& a = t->levels[2];
  const auto& b = t->levels[3];
  for (int j = 0; j < n; j += 7)
    for (int i = 0; i < n; i += 5) {
      const std::size_t p = static_cast<std::size_t>(2 * j) * (2 * n) + 2 * i;
      const glm::vec3 mean = 0.25f * (a[p] + a[p + 1] + a[p + 2 * n] + a[p + 2 * n + 1]);
      EXPECT_NEAR(b[static_cast<std::size_t>(j) * n + i].y, mean.y, 1e-6);
    }
}

// The spread of the albedo over many ground points seen the same way: near the eye the
// texture's, and where a pixel's footprint covers the land-use period (toward the horizon) almost
// none, with the mean kept: the ground does not shimmer there, and it keeps its colour.
TEST(GroundAlbedo, TheFootprintFilterRemovesTheVariationToTheHorizonAndKeepsTheMean) {
  const auto t = sky_ground_albedo();
  const double pixel = 2.0 * std::tan(0.5 * 60.0 * M_PI / 180.0) / 1280.0;
  const auto spread = [&](double distance_m, double eye_height_m, double& mean) {
    const glm::dvec3 dir = glm::normalize(glm::dvec3(0.0, -eye_height_m, -distance_m));
    std::vector<double> l;
    mean = 0.0;
    for (int k = 0; k < 400; ++k) {
      const double x = 137.1 * k, z = -distance_m + 91.7 * (k % 23);
      l.push_back(luminance(ground_albedo(*t, x, z, dir, distance_m, pixel)));
      mean += l.back() / 400.0;
    }
    double var = 0.0;
    for (double v : l) var += (v - mean) * (v - mean) / 400.0;
    return std::sqrt(var);
  };
  double near_mean = 0.0, far_mean = 0.0;
  const double near_sd = spread(1500.0, 300.0, near_mean);
  const double far_sd = spread(300000.0, 300.0, far_mean);
  EXPECT_GT(near_sd, 0.1 * t->mean_luminance);
  EXPECT_LT(far_sd, 0.1 * near_sd);
  EXPECT_NEAR(far_mean / t->mean_luminance, 1.0, 0.05);
  EXPECT_NEAR(near_mean / t->mean_luminance, 1.0, 0.15);
}

TEST(GroundAlbedo, TheSkySceneHasItAndBadParametersAreRefused) {
  const Scene s = make_scene("sky");
  ASSERT_TRUE(s.ground.has_value());
  EXPECT_EQ(s.ground->albedo_texture, sky_ground_albedo());
  GroundAlbedoParams p;
  p.size = 300;
  EXPECT_THROW(bake_ground_albedo(p), std::invalid_argument);
  p = GroundAlbedoParams{};
  p.period_m = 0.0;
  EXPECT_THROW(bake_ground_albedo(p), std::invalid_argument);
}

}  // namespace
}  // namespace nimbus::render
