// Parameter validation: validate() and the NoiseField constructor reject bad parameters with
// std::invalid_argument whose message names the parameter, and accept the edge values that
// are documented as valid.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include "nimbus/noise/noise.hpp"

namespace nimbus::noise {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Expects both validate(p) and NoiseField(p) to throw std::invalid_argument mentioning `word`.
void expect_rejected(const NoiseParams& p, const std::string& word, const std::string& what) {
  for (int path = 0; path < 2; ++path) {
    try {
      if (path == 0) {
        validate(p);
      } else {
        const NoiseField f(p);
      }
      ADD_FAILURE() << what << ": " << (path ? "NoiseField" : "validate") << " accepted it";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos)
          << what << ": message \"" << e.what() << "\" does not name \"" << word << "\"";
    } catch (const std::exception& e) {
      ADD_FAILURE() << what << ": threw something other than std::invalid_argument: " << e.what();
    }
  }
}

NoiseParams with(const std::function<void(NoiseParams&)>& change) {
  NoiseParams p;
  change(p);
  return p;
}

TEST(NoisePropsParams, BadParametersAreRejectedByName) {
  expect_rejected(with([](NoiseParams& p) { p.fractal = Fractal::Fbm; p.octaves = 0; }), "octaves", "octaves 0");
  expect_rejected(with([](NoiseParams& p) { p.fractal = Fractal::Fbm; p.octaves = 25; }), "octaves", "octaves 25");
  expect_rejected(with([](NoiseParams& p) { p.fractal = Fractal::Ridged; p.octaves = -3; }), "octaves", "octaves -3");
  for (double f : {kNaN, kInf, -kInf, 0.0, -0.0, -1.0, -1e-9})
    expect_rejected(with([f](NoiseParams& p) { p.frequency = f; }), "frequency", "frequency " + std::to_string(f));
  for (double l : {1.0, 0.5, 0.0, -2.0, kNaN, kInf})
    expect_rejected(with([l](NoiseParams& p) { p.fractal = Fractal::Fbm; p.octaves = 3; p.lacunarity = l; }),
                    "lacunarity", "lacunarity " + std::to_string(l));
  for (double g : {0.0, -0.5, 1.5, kNaN})
    expect_rejected(with([g](NoiseParams& p) { p.fractal = Fractal::Fbm; p.octaves = 3; p.gain = g; }),
                    "gain", "gain " + std::to_string(g));
  for (double t : {kNaN, kInf, -kInf})
    expect_rejected(with([t](NoiseParams& p) { p.time = t; }), "time", "time " + std::to_string(t));
  for (int axis = 0; axis < 3; ++axis)
    expect_rejected(with([axis](NoiseParams& p) { p.period[axis] = -4; }), "period", "negative period");
  expect_rejected(with([](NoiseParams& p) { p.kind = Kind::Wavelet; p.period = {32, 32, 16}; }), "period",
                  "wavelet periods unequal");
  expect_rejected(with([](NoiseParams& p) { p.kind = Kind::Wavelet; p.period = {33, 33, 33}; }), "period",
                  "wavelet period odd");
  expect_rejected(with([](NoiseParams& p) { p.kind = Kind::Wavelet; p.period = {6, 6, 6}; }), "period",
                  "wavelet period below 8");
  expect_rejected(with([](NoiseParams& p) { p.kind = Kind::Gradient; p.projected = true; }), "projected",
                  "projected gradient noise");
  expect_rejected(with([](NoiseParams& p) { p.kind = Kind::Value; p.projected = true; }), "projected",
                  "projected value noise");
  expect_rejected(with([](NoiseParams& p) { p.kind = Kind::Wavelet; p.projected = true; p.normal = {0, 0, 0}; }),
                  "normal", "zero projection normal");
  expect_rejected(with([](NoiseParams& p) { p.kind = Kind::Wavelet; p.tile_size = 9; }), "tile size", "odd tile");
  expect_rejected(with([](NoiseParams& p) {
                    p.fractal = Fractal::Fbm; p.octaves = 3; p.lacunarity = 2.5; p.period = {4, 4, 4};
                  }),
                  "lacunarity", "periodic fBm with a non-integer lacunarity");
}

TEST(NoisePropsParams, DocumentedEdgeValuesAreAccepted) {
  // Octaves are ignored without a fractal sum.
  EXPECT_NO_THROW(validate(with([](NoiseParams& p) { p.octaves = 0; })));
  EXPECT_NO_THROW(validate(with([](NoiseParams& p) { p.fractal = Fractal::Fbm; p.octaves = 1; })));
  EXPECT_NO_THROW(validate(with([](NoiseParams& p) { p.fractal = Fractal::Fbm; p.octaves = kMaxOctaves; })));
  EXPECT_NO_THROW(validate(with([](NoiseParams& p) { p.fractal = Fractal::Fbm; p.octaves = 3; p.gain = 1.0; })));
  EXPECT_NO_THROW(validate(with([](NoiseParams& p) { p.fractal = Fractal::Fbm; p.octaves = 3; p.lacunarity = 1.01; })));
  EXPECT_NO_THROW(validate(with([](NoiseParams& p) { p.time = -123.5; })));
  EXPECT_NO_THROW(validate(with([](NoiseParams& p) { p.period = {5, 0, 16}; })));
  EXPECT_NO_THROW(validate(with([](NoiseParams& p) { p.kind = Kind::Wavelet; p.period = {8, 8, 8}; })));
  EXPECT_NO_THROW(validate(with([](NoiseParams& p) { p.kind = Kind::Wavelet; p.projected = true; p.normal = {0, 3, 4}; })));
  // The projection normal is normalised by the field.
  const NoiseField f(with([](NoiseParams& p) { p.kind = Kind::Wavelet; p.projected = true; p.normal = {0, 3, 4}; }));
  EXPECT_NEAR(f.params().normal[1], 0.6, 1e-15);
  EXPECT_NEAR(f.params().normal[2], 0.8, 1e-15);
}

TEST(NoisePropsParams, NamesRoundTrip) {
  for (Kind k : {Kind::Value, Kind::Gradient, Kind::Wavelet}) EXPECT_EQ(parse_kind(to_string(k)), k);
  for (Fractal f : {Fractal::None, Fractal::Fbm, Fractal::Turbulence, Fractal::Ridged})
    EXPECT_EQ(parse_fractal(to_string(f)), f);
  EXPECT_FALSE(parse_kind("perlin").has_value());
  EXPECT_FALSE(parse_fractal("").has_value());
}

}  // namespace
}  // namespace nimbus::noise
