// Sequence patterns (nimbus/base/sequence_pattern.hpp): the names printf would make for the
// accepted fields, and a refusal for every other use of '%', so no user text reaches a format.
#include <gtest/gtest.h>

#include <climits>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "nimbus/base/sequence_pattern.hpp"

namespace nimbus {
namespace {

// The anchor: printf itself, given only the field (a constant format here, never user text).
std::string printf_field(int width, long frame) {
  char format[8], out[64];
  if (width == 0) std::snprintf(format, sizeof format, "%%ld");
  else std::snprintf(format, sizeof format, "%%0%dld", width);
  std::snprintf(out, sizeof out, format, frame);
  return out;
}

TEST(SequencePattern, NamesAreWhatPrintfWritesForEveryWidthAndSign) {
  for (int width = 0; width <= 9; ++width) {
    const std::string field = width == 0 ? "%d" : "%0" + std::to_string(width) + "d";
    const SequencePattern p = SequencePattern::parse("dir/cloud." + field + ".vdb", "-o");
    ASSERT_TRUE(p.has_field);
    EXPECT_EQ(p.head, "dir/cloud.");
    EXPECT_EQ(p.tail, ".vdb");
    for (long frame : {0L, 7L, -7L, 1001L, -99999L, 9999999L, 123456789012L, LONG_MIN + 1, LONG_MAX})
      EXPECT_EQ(p.path(frame), "dir/cloud." + printf_field(width, frame) + ".vdb") << field << " " << frame;
  }
  EXPECT_EQ(frame_number_text(LONG_MIN, 4), printf_field(4, LONG_MIN));
}

TEST(SequencePattern, ANameWithoutAFieldIsOneFile) {
  const SequencePattern p = SequencePattern::parse("cloud.vdb", "-o");
  EXPECT_FALSE(p.has_field);
  EXPECT_EQ(p.path(5), "cloud.vdb");
  EXPECT_EQ(p.path(-5), "cloud.vdb");
}

TEST(SequencePattern, EveryOtherPercentIsRefusedNamingTheInput) {
  for (const char* bad : {"%s", "x%0s.vdb", "%n%n", "%s%s%s%s", "%99999999d", "a%099d.vdb", "%0d", "%4d", "%x", "%ld",
                          "%%", "a%", "%0", "%010d", "%d%d", "%04d.%s", "%-4d", "%+d", "% d", "%.3d", "%*d"}) {
    try {
      SequencePattern::parse(bad, "--thing");
      ADD_FAILURE() << bad << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--thing '", 0), 0u) << e.what();
    }
  }
}

TEST(SequencePattern, EchoedPatternsAreShortAndOneLine) {
  const std::string hostile = "\x1b[2J" + std::string(10000, 'a') + "\n%s";
  try {
    SequencePattern::parse(hostile, "-o");
    FAIL();
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_LT(what.size(), 200u);
    EXPECT_EQ(what.find('\x1b'), std::string::npos);
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
}

}  // namespace
}  // namespace nimbus
