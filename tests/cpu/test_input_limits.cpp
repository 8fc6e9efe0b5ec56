// The input limits (base/input_limits.hpp): files refused by kind and size before reading, JSON
// nesting refused before parsing, stdin lines bounded, and echoed values kept short.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <sstream>
#include <stdexcept>

#include "nimbus/base/input_limits.hpp"
#include "support/vdb_fixtures.hpp"

namespace nimbus::test {
namespace {

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(InputLimits, ARegularFileWithinTheLimitIsReadWhole) {
  TempDir d;
  const std::string text = std::string(1000, 'x') + "\n\0end";
  write_bytes(d / "a.json", text);
  EXPECT_EQ(read_regular_file((d / "a.json").string(), "test", 1005), text);
}

TEST(InputLimits, FilesOverTheLimitOrNotRegularAreRefusedNamingThem) {
  TempDir d;
  write_bytes(d / "big.json", std::string(1001, 'x'));
  ::mkfifo((d / "fifo").c_str(), 0600);
  const std::string big = (d / "big.json").string();
  EXPECT_EQ(error_of([&] { read_regular_file(big, "--params " + big, 1000); }).rfind("--params " + big + ": ", 0), 0u);
  EXPECT_NE(error_of([&] { read_regular_file(big, "x", 1000); }).find("larger than the limit"), std::string::npos);
  EXPECT_EQ(read_regular_file(big, "x", 1001).size(), 1001u);
  // A FIFO is refused before it is opened (opening it would wait for a writer), devices too.
  EXPECT_NE(error_of([&] { read_regular_file((d / "fifo").string(), "x"); }).find("is a FIFO"), std::string::npos);
  EXPECT_NE(error_of([&] { read_regular_file("/dev/zero", "x"); }).find("is a character device"), std::string::npos);
  EXPECT_NE(error_of([&] { read_regular_file(d.path.string(), "x"); }).find("is a directory"), std::string::npos);
  EXPECT_NE(error_of([&] { read_regular_file((d / "missing").string(), "x"); }).find("cannot be read"), std::string::npos);
}

TEST(InputLimits, SpecialFilesAreRefusedAndMissingOnesLeftToTheReader) {
  TempDir d;
  write_bytes(d / "a.vdb", "x");
  ::mkfifo((d / "fifo").c_str(), 0600);
  EXPECT_NO_THROW(refuse_special_file((d / "a.vdb").string(), "FILE"));
  EXPECT_NO_THROW(refuse_special_file((d / "missing.vdb").string(), "FILE"));
  EXPECT_NE(error_of([&] { refuse_special_file((d / "fifo").string(), "FILE"); }).find("FILE '" + (d / "fifo").string() + "': is a FIFO"),
            std::string::npos);
  EXPECT_NE(error_of([&] { refuse_special_file("/dev/null", "TEST"); }).find("is a character device"), std::string::npos);
}

TEST(InputLimits, JsonDepthCountsBracketsOutsideStrings) {
  EXPECT_NO_THROW(check_json_depth(std::string(64, '[') + std::string(64, ']'), "x"));
  EXPECT_NE(error_of([] { check_json_depth(std::string(65, '['), "--params 'p'"); }).find("nested deeper than 64"),
            std::string::npos);
  EXPECT_NE(error_of([] { check_json_depth(R"({"a": {"b": [[1]]}})", "x", 3); }), "");
  EXPECT_NO_THROW(check_json_depth(R"({"a": {"b": [1]}})", "x", 3));
  // Brackets inside strings, escaped quotes included, are text, not nesting.
  EXPECT_NO_THROW(check_json_depth(R"(["[[[[", "\"[[[[", "{{{{"])", "x", 1));
  // Closing brackets do not take the depth below zero and so hide later nesting.
  EXPECT_NE(error_of([] { check_json_depth("]]]]" + std::string(3, '['), "x", 2); }), "");
}

TEST(InputLimits, LinesAreReadUpToTheirLimit) {
  std::istringstream in("ab\r\ncdef\n\nlast");
  std::string line;
  EXPECT_EQ(read_line_limited(in, line, 4), LineRead::Line);
  EXPECT_EQ(line, "ab");
  EXPECT_EQ(read_line_limited(in, line, 4), LineRead::Line);
  EXPECT_EQ(line, "cdef");
  EXPECT_EQ(read_line_limited(in, line, 4), LineRead::Line);
  EXPECT_EQ(line, "");
  EXPECT_EQ(read_line_limited(in, line, 4), LineRead::Line);
  EXPECT_EQ(line, "last");
  EXPECT_EQ(read_line_limited(in, line, 4), LineRead::End);
  std::istringstream endless(std::string(100, '0'));
  EXPECT_EQ(read_line_limited(endless, line, 10), LineRead::TooLong);
  EXPECT_LE(line.size(), 10u);
}

TEST(InputLimits, EchoedValuesAreShortAndPrintable) {
  EXPECT_EQ(echo("abc"), "abc");
  EXPECT_EQ(echo(std::string(41, 'x')), std::string(40, 'x') + "...");
  EXPECT_EQ(echo(std::string(40, 'x')), std::string(40, 'x'));
  EXPECT_EQ(echo("a\nb\x1b"), "a?b?");
}

}  // namespace
}  // namespace nimbus::test
