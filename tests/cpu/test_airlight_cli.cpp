// nimbus airlight: CSV rows in, one La per line out, the same numbers as the library; bad rows
// are usage errors (exit 2) naming the line and the field.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "nimbus/render/media/airlight.hpp"
#include "support/run_nimbus.hpp"

namespace {

using nimbus::render::AirlightQuery;
using nimbus::test::run_nimbus;

std::filesystem::path write_input(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / ("nimbus_airlight_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path;
}

const char* kRows =
    "0.04,100,30,55,0.6\n"
    "1,1,10,inf,3.13\n"
    " 0.5 , 2 , 4 , 1e3 , 1e-3 \n"
    "0.001,1,5,inf,1.5707963267948966\n"
    "0,1,1,inf,1\r\n";

std::vector<AirlightQuery> rows() {
  const double inf = std::numeric_limits<double>::infinity();
  return {{0.04, 100, 30, 55, 0.6}, {1, 1, 10, inf, 3.13}, {0.5, 2, 4, 1e3, 1e-3}, {0.001, 1, 5, inf, 1.5707963267948966},
          {0, 1, 1, inf, 1}};
}

std::string expected_output(const std::vector<double>& values) {
  std::string out;
  char buf[64];
  for (double v : values) {
    std::snprintf(buf, sizeof buf, "%.9g\n", v);
    out += buf;
  }
  return out;
}

TEST(AirlightCli, EveryCpuMethodPrintsWhatTheLibraryComputes) {
  const auto input = write_input("rows.csv", kRows);
  for (const char* method : {"stable", "quadrature", "table:64", "raymarch:500"}) {
    const auto r = run_nimbus("airlight --method " + std::string(method) + " < " + input.string());
    ASSERT_EQ(r.code, 0) << method << ": " << r.output;
    const auto m = nimbus::render::parse_airlight_method(method);
    EXPECT_EQ(r.output, expected_output(nimbus::render::evaluate_airlight(rows(), m))) << method;
  }
  // The default method is stable; its answers are within the target of the reference.
  const auto stable = run_nimbus("airlight < " + input.string());
  const auto quad = run_nimbus("airlight --method quadrature < " + input.string());
  std::istringstream a(stable.output), b(quad.output);
  double x, y;
  int n = 0;
  while (a >> x && b >> y) {
    if (y == 0.0) {
      EXPECT_EQ(x, 0.0);
    } else {
      EXPECT_NEAR(x / y, 1.0, 1e-3) << n;
    }
    ++n;
  }
  EXPECT_EQ(n, 5);
}

TEST(AirlightCli, BadRowsAreUsageErrorsNamingLineAndField) {
  struct Case {
    const char* text;
    const char* expect;
  };
  const Case cases[] = {
      {"1,1,1,1,1\n1,1,-2,1,1\n", "line 2, field Dsv"},
      {"1,1,1,1,1\n1,1,1,1,1\nnan,1,1,1,1\n", "line 3, field beta"},
      {"1,1,1,1,3.2\n", "line 1, field gamma"},
      {"1,1,1,1,-0.1\n", "line 1, field gamma"},
      {"1,1,1,inf,1\n1,1,1,1\n", "line 2: expected 5 fields"},
      {"1,1,1,1,1,1\n", "line 1: expected 5 fields"},
      {"beta,I0,Dsv,Dvp,gamma\n", "line 1, field beta: 'beta' is not a number"},
      {"1,1,1,1,1\n\n", "line 2: expected 5 fields"},
      {"1,1,1,1,0.5x\n", "line 1, field gamma: '0.5x' is not a number"},
      {"1,inf,1,1,1\n", "line 1, field I0"},
      {"1,1,1,-inf,1\n", "line 1, field Dvp"},
  };
  int k = 0;
  for (const Case& c : cases) {
    const auto input = write_input("bad" + std::to_string(k++) + ".csv", c.text);
    const auto r = run_nimbus("airlight --method stable < " + input.string());
    EXPECT_EQ(r.code, 2) << c.text << r.output;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << "expected '" << c.expect << "' in: " << r.output;
  }
  const auto input = write_input("good.csv", "1,1,1,1,1\n");
  for (const char* args : {"--method table:8", "--method table:x", "--method raymarch:0", "--method simpson",
                           "--device cuda", "--method quadrature --device gl"}) {
    const auto r = run_nimbus("airlight " + std::string(args) + " < " + input.string());
    EXPECT_EQ(r.code, 2) << args << ": " << r.output;
  }
}

TEST(AirlightCli, PhaseOptionReplacesTheIsotropicPhase) {
  const auto input = write_input("phase.csv", kRows);
  const nimbus::render::Phase hg{nimbus::render::PhaseKind::HenyeyGreenstein, 0.9};
  for (const char* method : {"stable", "quadrature", "raymarch:300"}) {
    const auto r = run_nimbus("airlight --phase hg:0.9 --method " + std::string(method) + " < " + input.string());
    ASSERT_EQ(r.code, 0) << method << ": " << r.output;
    const auto m = nimbus::render::parse_airlight_method(method);
    EXPECT_EQ(r.output, expected_output(nimbus::render::evaluate_airlight(rows(), m, hg))) << method;
  }
  // Forward scattering brightens the glow around a lamp seen straight ahead (row 3: gamma =
  // 1e-3) and dims the light scattered back from a lamp behind the viewer (row 2: gamma = 3.13).
  const auto iso = nimbus::render::evaluate_airlight(rows(), {nimbus::render::AirlightMethod::Quadrature, 0});
  const auto fwd = nimbus::render::evaluate_airlight(rows(), {nimbus::render::AirlightMethod::Quadrature, 0}, hg);
  EXPECT_GT(fwd[2], 2.0 * iso[2]);
  EXPECT_LT(fwd[1], 0.1 * iso[1]);
  for (const char* args : {"--phase hg:0.9 --method table:64", "--phase hg:1.5", "--phase mie"}) {
    const auto r = run_nimbus("airlight " + std::string(args) + " < " + input.string());
    EXPECT_EQ(r.code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find("--phase"), std::string::npos) << r.output;
  }
}

TEST(AirlightCli, EmptyInputGivesEmptyOutput) {
  const auto input = write_input("empty.csv", "");
  const auto r = run_nimbus("airlight < " + input.string());
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.output, "");
}

}  // namespace
