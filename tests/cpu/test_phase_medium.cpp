// Medium validation: each bad coefficient is named.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "nimbus/render/media/medium.hpp"

namespace {

using nimbus::render::Medium;

std::string error_of(const Medium& m) {
  try {
    nimbus::render::validate(m);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(PhaseMedium, ValidMediaPassAndBadFieldsAreNamed) {
  EXPECT_EQ(error_of(Medium{}), "");
  Medium clear;
  clear.extinction_per_m = 0.0;
  clear.albedo = 0.0;
  EXPECT_EQ(error_of(clear), "");
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (double bad : {-0.1, nan, inf}) {
    Medium m;
    m.extinction_per_m = bad;
    EXPECT_NE(error_of(m).find("extinction_per_m"), std::string::npos) << bad;
  }
  for (double bad : {-0.1, 1.5, nan}) {
    Medium m;
    m.albedo = bad;
    EXPECT_NE(error_of(m).find("albedo"), std::string::npos) << bad;
  }
  Medium m;
  m.phase = {nimbus::render::PhaseKind::HenyeyGreenstein, 1.0};
  EXPECT_NE(error_of(m).find("phase g"), std::string::npos);
  const Medium half{0.04, 0.5, {}};
  EXPECT_DOUBLE_EQ(half.scattering_per_m(), 0.02);
}

}  // namespace
