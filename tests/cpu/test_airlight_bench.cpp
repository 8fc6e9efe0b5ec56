// nimbus bench airlight: the table has the quadrature anchor and one row per method and device,
// the stable rows' errors meet the target, the table's are larger; bad options exit 2.
#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>
#include <string>

#include "support/run_nimbus.hpp"

namespace {

using nimbus::test::run_nimbus;

struct Row {
  bool found = false;
  double ns = 0.0, max_err = 0.0, median = 0.0;
  std::string compile;
};

// "| method | device | ns | compile | max | rms | median |"
Row find_row(const std::string& output, const std::string& method, const std::string& device) {
  std::istringstream in(output);
  const std::string head = "| " + method + " | " + device + " | ";
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(head, 0) != 0) continue;
    Row r;
    char compile[32] = {0};
    double rms = 0.0;
    if (std::sscanf(line.c_str() + head.size(), "%lf | %31s | %lf | %lf | %lf |", &r.ns, compile, &r.max_err, &rms,
                    &r.median) == 5) {
      r.found = true;
      r.compile = compile;
    }
    return r;
  }
  return {};
}

TEST(AirlightBench, CpuTableHasTheAnchorAndMeasuredRows) {
  const auto r = run_nimbus("bench airlight --quick --devices cpu --methods stable,table:16,raymarch:16");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("| quadrature | cpu | "), std::string::npos) << r.output;
  const Row stable = find_row(r.output, "stable", "cpu"), table = find_row(r.output, "table:16", "cpu"),
            march = find_row(r.output, "raymarch:16", "cpu");
  ASSERT_TRUE(stable.found && table.found && march.found) << r.output;
  EXPECT_GT(stable.ns, 0.0);
  EXPECT_EQ(stable.compile, "-");  // no compile step on the CPU
  EXPECT_LE(stable.max_err, 1e-3) << r.output;
  EXPECT_GT(table.median, stable.max_err) << r.output;  // a 16 x 16 table is a few per cent off
}

TEST(AirlightBench, GlRowsTimeTheShaderWithItsCompile) {
  const auto r = run_nimbus("bench airlight --quick --devices gl --methods stable,raymarch:16");
  if (r.output.find("no GL rows") != std::string::npos) GTEST_SKIP() << r.output;
  ASSERT_EQ(r.code, 0) << r.output;
  const Row stable = find_row(r.output, "stable", "gl");
  ASSERT_TRUE(stable.found && find_row(r.output, "raymarch:16", "gl").found) << r.output;
  EXPECT_GT(stable.ns, 0.0);
  EXPECT_GT(std::stod(stable.compile), 0.0);
  EXPECT_LE(stable.max_err, 1e-3) << r.output;
}

TEST(AirlightBench, BadOptionsAreUsageErrors) {
  for (const char* args : {"--methods quadrature", "--methods stable,table:8", "--methods table:16 --phase hg:0.5",
                           "--log2-n 3", "--devices tpu", "--phase hg:2", "--error-queries 0"}) {
    const auto r = run_nimbus(std::string("bench airlight --quick ") + args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
    const std::string option = std::string(args).substr(0, std::string(args).find(' '));
    EXPECT_NE(r.output.find(option), std::string::npos) << args << "\n" << r.output;
  }
}

}  // namespace
