// EXR files: a round trip within half precision with the metadata, a header that an independent
// tool (OpenEXR's exrheader) reads as ZIP with our attributes, refusals of bad pixels and names
// before anything is written, and clear errors for unwritable, missing and corrupt files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "nimbus/render/image/image_io.hpp"
#include "support/run_nimbus.hpp"
#include "support/vdb_fixtures.hpp"

namespace {

using nimbus::render::Image;
using nimbus::render::read_exr;
using nimbus::render::write_exr;
using nimbus::test::count_temp_files;
using nimbus::test::TempDir;

// Runs `f`, expects exception E whose message contains every one of `mentions`.
template <class E, class F>
void expect_error(F&& f, std::initializer_list<std::string> mentions) {
  try {
    f();
    ADD_FAILURE() << "no exception";
  } catch (const E& e) {
    for (const std::string& m : mentions) EXPECT_NE(std::string(e.what()).find(m), std::string::npos) << e.what();
  }
}

// Values over 9 decades (all normal half floats), zeros, and alpha in [0, 1].
Image test_image(int w, int h) {
  Image im(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      float* p = im.pixel(x, y);
      const int i = y * w + x;
      for (int c = 0; c < 3; ++c) p[c] = (i + c) % 11 == 0 ? 0.0f : std::pow(10.0f, -4.0f + 8.5f * ((i * 7 + c * 3) % 29) / 28.0f);
      p[3] = static_cast<float>(x) / (w - 1);
    }
  }
  im.metadata = {{"camera", "eye=0,1.7,10 look_at=0,1.7,0 up=0,1,0 fov=60"},
                 {"method", "raymarch:64"},
                 {"medium", "beta=0.04 albedo=0.9 phase=hg:0.3"},
                 {"empty", ""},
                 {"a_rather_long_attribute_name_beyond_31_characters", "long names work"}};
  return im;
}

TEST(ImageExr, RoundTripWithinHalfPrecisionWithMetadata) {
  TempDir dir;
  Image im = test_image(13, 7);
  im.pixel(2, 3)[0] = 1e6f;  // above the half range: clamped to 65504
  write_exr(dir / "a.exr", im);
  const Image back = read_exr(dir / "a.exr");
  ASSERT_EQ(back.width, 13);
  ASSERT_EQ(back.height, 7);
  for (int y = 0; y < 7; ++y) {
    for (int x = 0; x < 13; ++x) {
      for (int c = 0; c < 4; ++c) {
        const double want = std::min(im.pixel(x, y)[c], 65504.0f);
        // Half floats keep 11 significant bits: round to nearest is within 2^-11 relative.
        EXPECT_LE(std::abs(back.pixel(x, y)[c] - want), std::ldexp(want, -11)) << x << "," << y << " c" << c;
      }
    }
  }
  EXPECT_EQ(back.pixel(2, 3)[0], 65504.0f);
  for (const auto& [key, value] : im.metadata) {
    ASSERT_TRUE(back.metadata.count(key)) << key;
    EXPECT_EQ(back.metadata.at(key), value) << key;
  }
  EXPECT_FALSE(back.metadata.at("nimbus_version").empty());
  EXPECT_NE(back.metadata.at("comments").find("premultiplied"), std::string::npos);
  EXPECT_EQ(back.metadata.count("type"), 0u);  // EXR's own attribute, not metadata
  // What was read writes again, and reads back the same.
  write_exr(dir / "b.exr", back);
  EXPECT_EQ(read_exr(dir / "b.exr").rgba, back.rgba);
}

TEST(ImageExr, ExrheaderSeesZipHalfChannelsAndAttributes) {
  const auto which = nimbus::test::run_command("which exrheader");
  if (which.code != 0) GTEST_SKIP() << "exrheader not installed (Debian package openexr)";
  TempDir dir;
  write_exr(dir / "a.exr", test_image(5, 4));
  const auto r = nimbus::test::run_command("exrheader " + (dir / "a.exr").string());
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* want : {"compression (type compression): zip", "A, 16-bit floating-point",
                           "B, 16-bit floating-point", "G, 16-bit floating-point", "R, 16-bit floating-point",
                           "method (type string): \"raymarch:64\"", "camera (type string): \"eye=0,1.7,10",
                           "nimbus_version (type string)", "comments (type string)", "chromaticities",
                           "dataWindow (type box2i): (0 0) - (4 3)"}) {
    EXPECT_NE(r.output.find(want), std::string::npos) << want << "\n" << r.output;
  }
}

TEST(ImageExr, BadPixelsAreRefusedByPixelAndChannelAndNothingIsWritten) {
  TempDir dir;
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  for (const auto& [value, word] : {std::pair{nan, "NaN"}, std::pair{inf, "Inf"}, std::pair{-inf, "Inf"},
                                    std::pair{-0.5f, "negative"}}) {
    Image im = test_image(6, 5);
    im.pixel(4, 2)[1] = value;
    expect_error<std::invalid_argument>([&] { write_exr(dir / "a.exr", im); }, {"pixel (4, 2)", "channel G", word});
  }
  Image wrong_size = test_image(6, 5);
  wrong_size.rgba.pop_back();
  expect_error<std::invalid_argument>([&] { write_exr(dir / "a.exr", wrong_size); }, {"6x5", "119"});
  expect_error<std::invalid_argument>([&] { write_exr(dir / "a.exr", Image()); }, {"empty"});
  expect_error<std::invalid_argument>([&] { write_exr(dir / "a.exr", Image(0, 3)); }, {"empty", "0x3"});
  EXPECT_FALSE(std::filesystem::exists(dir / "a.exr"));
  EXPECT_EQ(count_temp_files(dir.path), 0);
}

TEST(ImageExr, ReservedOrEmptyMetadataNamesAreRefused) {
  TempDir dir;
  for (const char* key : {"compression", "channels", "dataWindow", "type", "name", "tiles"}) {
    Image im = test_image(3, 3);
    im.metadata[key] = "x";
    expect_error<std::invalid_argument>([&] { write_exr(dir / "a.exr", im); }, {key, "reserved"});
  }
  Image im = test_image(3, 3);
  im.metadata[""] = "x";
  expect_error<std::invalid_argument>([&] { write_exr(dir / "a.exr", im); }, {"empty attribute name"});
  EXPECT_FALSE(std::filesystem::exists(dir / "a.exr"));
}

TEST(ImageExr, UnwritableOutputNamesThePathAndLeavesNoFile) {
  TempDir dir;
  nimbus::test::write_bytes(dir / "file", "not a directory");
  const auto inside_file = dir / "file" / "a.exr";
  expect_error<std::runtime_error>([&] { write_exr(inside_file, test_image(3, 3)); }, {(dir / "file").string()});
  std::filesystem::create_directory(dir / "out.exr");
  expect_error<std::runtime_error>([&] { write_exr(dir / "out.exr", test_image(3, 3)); }, {"out.exr"});
  EXPECT_TRUE(std::filesystem::is_directory(dir / "out.exr"));
  EXPECT_EQ(count_temp_files(dir.path), 0);
  // A good file is never replaced by a failed write.
  write_exr(dir / "good.exr", test_image(3, 3));
  const std::string before = nimbus::test::read_bytes(dir / "good.exr");
  Image bad = test_image(3, 3);
  bad.pixel(0, 0)[0] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(write_exr(dir / "good.exr", bad), std::invalid_argument);
  EXPECT_EQ(nimbus::test::read_bytes(dir / "good.exr"), before);
}

TEST(ImageExr, MissingAndCorruptFilesNameThePath) {
  TempDir dir;
  expect_error<std::runtime_error>([&] { read_exr(dir / "missing.exr"); }, {(dir / "missing.exr").string()});
  nimbus::test::write_bytes(dir / "text.exr", "this is not an EXR file at all");
  expect_error<std::runtime_error>([&] { read_exr(dir / "text.exr"); }, {(dir / "text.exr").string()});
  // A real file cut short: the header survives, the pixel data does not.
  write_exr(dir / "a.exr", test_image(64, 64));
  const std::string bytes = nimbus::test::read_bytes(dir / "a.exr");
  nimbus::test::write_bytes(dir / "cut.exr", bytes.substr(0, bytes.size() / 2));
  expect_error<std::runtime_error>([&] { read_exr(dir / "cut.exr"); }, {(dir / "cut.exr").string()});
}

}  // namespace
