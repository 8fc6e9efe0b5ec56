// Realism: nimbus's cloud fields measured the way observers measure real ones. The outlines
// are the vertically integrated optical depth thresholded at 1, clouds touching the map's edge
// excluded.
//   - perimeter-area fractal dimension D of the cumulus field: observed 1.35 (Lovejoy 1982),
//     1.33-1.38 in later studies; asserted within [1.25, 1.45] over at least 30 clouds;
//   - cloud area distribution dn/dlog a ~ a^-b of the same field: observed about 0.87
//     (DeWitt et al. 2024); asserted within [0.6, 1.2], bins under 24 clouds dropped;
//   - the stratocumulus field's 1-D optical-depth spectrum between 200 m and 5 km, along the
//     wind and across it: observed -5/3 (Cahalan & Snider 1989); asserted within [-2.0, -1.3].
// Each test prints its figure; docs/volume.md tabulates them.
#include <gtest/gtest.h>

#include <cstdio>

#include "support/cloud_stats.hpp"
#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/preset.hpp"

namespace nimbus::volume {
namespace {

using test::CloudOutline;
using test::MapAxis;
using test::OpticalDepthMap;
using test::PowerLawFit;
using test::area_exponent;
using test::cloud_outlines;
using test::perimeter_area_dimension;
using test::spectrum_slope;
using test::vertical_optical_depth;

constexpr double kExtinctionPerM = 0.04;  // render::CloudOptics' default sigma_t per unit density

struct Field {
  OpticalDepthMap tau;
  std::vector<CloudOutline> clouds;
  double cloud_fraction = 0.0;
};

Field measure(const std::string& preset, double field_size_m, int crop) {
  const nlohmann::json doc = load_preset(preset);
  CloudParams p = cloud_from_json(doc.at("cloud"), preset);
  if (p.field && field_size_m > 0) p.field->size_m = {field_size_m, field_size_m};
  GenerateOptions o;
  o.voxel_size = doc.at("voxel_size").get<double>();
  const auto grid = generate_density(p, o);
  openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
  if (crop > 0) box = {{-crop, -crop, box.min().z()}, {crop - 1, crop - 1, box.max().z()}};
  Field f;
  f.tau = vertical_optical_depth(*grid, kExtinctionPerM, box);
  f.clouds = cloud_outlines(f.tau, 1.0);
  size_t cloudy = 0;
  for (double t : f.tau.tau) cloudy += t >= 1.0;
  f.cloud_fraction = double(cloudy) / double(f.tau.tau.size());
  return f;
}

// The cumulus field at its own voxel size, 20 x 20 km (four times the preset's area, for
// enough clouds in the area histogram's larger bins).
const Field& cumulus() {
  static const Field f = measure("cumulus-field", 20000.0, 0);
  return f;
}

TEST(CloudRealism, CumulusOutlinesHaveTheObservedFractalDimension) {
  const Field& f = cumulus();
  const PowerLawFit d = perimeter_area_dimension(f.clouds, 10);
  std::printf("cumulus-field: cloud fraction %.3f, %zu clouds; D = %.3f +- %.3f over %d clouds of >= 10 pixels "
              "(observed 1.35)\n",
              f.cloud_fraction, f.clouds.size(), d.exponent, d.standard_error, d.points);
  EXPECT_GE(d.points, 30);
  EXPECT_GE(d.exponent, 1.25);
  EXPECT_LE(d.exponent, 1.45);
}

TEST(CloudRealism, CumulusAreasFollowTheObservedPowerLaw) {
  const Field& f = cumulus();
  // Clouds of at least 25 pixels (0.01 km^2 at 20 m): below that, ragged edges shed specks.
  const PowerLawFit b = area_exponent(f.clouds, 5, 24, 25);
  std::printf("cumulus-field: area exponent b = %.3f +- %.3f over %d bins, areas %.3g to %.3g km^2 (observed 0.87)\n",
              b.exponent, b.standard_error, b.points, b.x_lo * 1e-6, b.x_hi * 1e-6);
  EXPECT_GE(b.points, 4);
  EXPECT_GE(b.exponent, 0.6);
  EXPECT_LE(b.exponent, 1.2);
}

TEST(CloudRealism, StratocumulusOpticalDepthSpectrumIsNearMinusFiveThirds) {
  // The central 8 km of the 10 km layer, away from its faded edges. The layer drifts along x.
  const Field f = measure("stratocumulus-field", 0.0, 160);
  for (MapAxis axis : {MapAxis::X, MapAxis::Y}) {
    const PowerLawFit s = spectrum_slope(f.tau, axis, 200.0, 5000.0);
    std::printf("stratocumulus-field: cloud fraction %.3f; spectrum slope %s the wind %.3f +- %.3f (observed -5/3)\n",
                f.cloud_fraction, axis == MapAxis::X ? "along" : "across", s.exponent, s.standard_error);
    EXPECT_GE(s.exponent, -2.0);
    EXPECT_LE(s.exponent, -1.3);
  }
}

TEST(CloudRealism, TheFbmGainSetsTheStratocumulusSlope) {
  // Lower gain, smoother layer, steeper spectrum: H = -log2(gain), noise slope -(2H + 1).
  const nlohmann::json base = load_preset("stratocumulus-field");
  double last = -100.0;
  for (double gain : {0.5, 0.79, 0.9}) {
    nlohmann::json doc = base;
    doc["cloud"]["gain"] = gain;
    CloudParams p = cloud_from_json(doc.at("cloud"), "stratocumulus-field");
    GenerateOptions o;
    o.voxel_size = doc.at("voxel_size").get<double>();
    const auto grid = generate_density(p, o);
    const openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
    const OpticalDepthMap tau =
        vertical_optical_depth(*grid, kExtinctionPerM, {{-160, -160, box.min().z()}, {159, 159, box.max().z()}});
    const double x = spectrum_slope(tau, MapAxis::X, 200.0, 5000.0).exponent;
    const double y = spectrum_slope(tau, MapAxis::Y, 200.0, 5000.0).exponent;
    const double noise_slope = -(2.0 * -std::log2(gain) + 1.0);
    std::printf("gain %.2f: optical-depth slope %.2f along, %.2f across (the noise alone: %.2f)\n", gain, x, y,
                noise_slope);
    EXPECT_GT(0.5 * (x + y), last) << "the slope must flatten as the gain rises";
    last = 0.5 * (x + y);
  }
}

}  // namespace
}  // namespace nimbus::volume
