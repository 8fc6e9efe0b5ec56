// `nimbus bench noise`: the quick run finishes, prints a row for every noise kind and shows
// that the SIMD paths match the scalar path bit for bit; bad options are usage errors (exit 2).
#include <gtest/gtest.h>

#include "support/run_nimbus.hpp"

#include <array>
#include <cstdio>
#include <string>

namespace {

using Result = nimbus::test::RunResult;
Result run(const std::string& args) { return nimbus::test::run_nimbus(args); }

TEST(BenchNoise, QuickRunPrintsEveryKindAndBitIdenticalPaths) {
  const Result r = run("bench noise --quick");
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* row : {"nimbus value, 1 octave", "nimbus gradient, 1 octave", "nimbus wavelet, 1 octave",
                          "nimbus value, 6-octave fBm", "nimbus gradient, 6-octave fBm",
                          "nimbus wavelet, 6-octave fBm", "Wavelet tile build", "Multi-threaded"})
    EXPECT_NE(r.output.find(row), std::string::npos) << row << "\n" << r.output;
  EXPECT_NE(r.output.find("bit-identical"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("NOT bit-identical"), std::string::npos) << r.output;
}

TEST(BenchNoise, BadOptionsAreUsageErrors) {
  for (const char* args : {"bench noise --repeats 0", "bench noise --repeats -3", "bench noise --res 4",
                           "bench noise --res 513"}) {
    const Result r = run(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
  }
  const Result r = run("bench noise --repeats 0");
  EXPECT_NE(r.output.find("--repeats"), std::string::npos) << r.output;
}

}  // namespace
