// The C++ side of the C++/GLSL contract (render/core/shader_contract.hpp, shaders/lib/contract.glsl):
// every enum value maps to its own code, the codes with no shader are refused, and the float phase
// functions the shaders run (compiled here as C++) pick the same function as the double reference
// for every kind, so a code mapped to the wrong kind fails here.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <stdexcept>
#include <vector>

#include "nimbus/render/media/airlight.hpp"
#include "nimbus/render/core/phase.hpp"
#include "nimbus/render/core/shader_contract.hpp"
#include "nimbus/render/media/shaft_method.hpp"

namespace nimbus::render {
namespace {

// Every fog phase kind (one lobe, with a shader code): the enum's values 0, 1, ... up to the first
// that phase_code refuses (the clouds' dual lobe, which the fog's shaders do not take).
// A kind added to the enum and mapped (the build insists) joins this list without anyone editing
// it, so the tests below cover it, and fail if lib/phase.glsl has no formula for it.
std::vector<PhaseKind> all_phase_kinds() {
  std::vector<PhaseKind> kinds;
  for (int k = 0; k < 64; ++k) {
    try {
      phase_code(static_cast<PhaseKind>(k));
    } catch (const std::invalid_argument&) {
      break;
    }
    kinds.push_back(static_cast<PhaseKind>(k));
  }
  return kinds;
}

TEST(ContractCodes, EveryPhaseKindHasItsOwnCode) {
  const std::vector<PhaseKind> kinds = all_phase_kinds();
  EXPECT_GE(kinds.size(), 4u);
  std::set<int> codes;
  for (PhaseKind k : kinds) codes.insert(phase_code(k));
  EXPECT_EQ(codes.size(), kinds.size());
  for (PhaseKind k : kinds) EXPECT_EQ(parse_phase(to_string(Phase{k, 0.5})).kind, k) << to_string(Phase{k, 0.5});
  EXPECT_EQ(phase_code(PhaseKind::Isotropic), contract::PHASE_ISOTROPIC);
  EXPECT_EQ(phase_code(PhaseKind::HenyeyGreenstein), contract::PHASE_HENYEY_GREENSTEIN);
  EXPECT_EQ(phase_code(PhaseKind::Schlick), contract::PHASE_SCHLICK);
  EXPECT_EQ(phase_code(PhaseKind::Rayleigh), contract::PHASE_RAYLEIGH);
}

// Each kind's float shader phase (through its code) equals the double reference of the same kind
// to float precision, and differs from every other kind somewhere: a swapped code cannot pass.
TEST(ContractCodes, EachPhaseCodeSelectsItsOwnFunction) {
  const double g = 0.6;
  const std::vector<PhaseKind> kinds = all_phase_kinds();
  for (PhaseKind k : kinds) {
    const Phase p{k, g};
    for (double mu = -1.0; mu <= 1.0; mu += 0.125) {
      const double ref = phase_value(p, mu);
      EXPECT_NEAR(phase_value_float(p, mu), ref, 2e-6 * ref + 1e-9) << to_string(p) << " cos " << mu;
    }
    for (PhaseKind other : kinds) {
      if (other == k) continue;
      double largest = 0.0;
      for (double mu = -1.0; mu <= 1.0; mu += 0.125)
        largest = std::max(largest, std::abs(phase_value_float(p, mu) - phase_value(Phase{other, g}, mu)) /
                                        phase_value(Phase{other, g}, mu));
      EXPECT_GT(largest, 0.05) << to_string(p) << " is indistinguishable from kind " << static_cast<int>(other);
    }
  }
}

TEST(ContractCodes, JitterAndMethodCodesAreDistinctAndTheCpuOnlyOnesAreRefused) {
  EXPECT_EQ(std::set<int>({jitter_code(Jitter::None), jitter_code(Jitter::White), jitter_code(Jitter::BlueNoise)}).size(),
            3u);
  EXPECT_EQ(jitter_code(Jitter::BlueNoise), contract::JITTER_BLUE_NOISE);
  EXPECT_EQ(std::set<int>({shaft_method_code(ShaftMethod::Kind::RayMarch), shaft_method_code(ShaftMethod::Kind::Analytic),
                           shaft_method_code(ShaftMethod::Kind::ShadowVolume)})
                .size(),
            3u);
  EXPECT_EQ(shaft_method_code(ShaftMethod::Kind::ShadowVolume), SHAFT_METHOD_SHADOW_VOLUME);
  EXPECT_THROW(shaft_method_code(ShaftMethod::Kind::Reference), std::invalid_argument);
  EXPECT_EQ(std::set<int>({airlight_eval_code(AirlightMethod::Stable), airlight_eval_code(AirlightMethod::Table),
                           airlight_eval_code(AirlightMethod::RayMarch)})
                .size(),
            3u);
  EXPECT_THROW(airlight_eval_code(AirlightMethod::Quadrature), std::invalid_argument);
}

TEST(ContractCodes, TextureUnitsAreDistinct) {
  const int units[] = {contract::UNIT_CLOUD_DENSITY, contract::UNIT_POINT_SHADOW,   contract::UNIT_SUN_SHADOW,
                       contract::UNIT_SURFACE_RADIANCE, contract::UNIT_SCENE_DISTANCE, contract::UNIT_JITTER,
                       contract::UNIT_SV_NEAR,          contract::UNIT_SV_FAR,         contract::UNIT_F_TABLE,
                       contract::UNIT_CLOUD_TAU,        contract::UNIT_CLOUD_RANGE,    contract::UNIT_LIGHT_BUFFER,
                       contract::UNIT_SCENE_COLOR,      contract::UNIT_CLOUD_COLOR,    contract::UNIT_CLOUD_DISTANCE,
                       contract::UNIT_CLOUD_DENSITY_NEXT, contract::UNIT_SKY_VIEW,     contract::UNIT_AERIAL_SCATTERING,
                       contract::UNIT_AERIAL_TRANSMITTANCE, contract::UNIT_LIGHT_VOLUME,
                       contract::UNIT_SURFACE_AIRLIGHT, contract::UNIT_LIGHT_RADIANCE};
  EXPECT_EQ(std::set<int>(std::begin(units), std::end(units)).size(), std::size(units));
  for (int u : units) {
    EXPECT_GE(u, 0);
    EXPECT_LT(u, 80) << "GL 4.5 guarantees 80 combined texture image units (and 16 samplers per stage)";
  }
  EXPECT_EQ(std::set<int>({contract::BLOCK_CAMERA, contract::BLOCK_LIGHTS, contract::BLOCK_CLOUD}).size(), 3u);
}

}  // namespace
}  // namespace nimbus::render
