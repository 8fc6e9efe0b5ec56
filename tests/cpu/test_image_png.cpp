// PNG previews, decoded again with libpng: the sRGB transfer curve on known greys, exposure,
// the three tone curves' defining values, row 0 at the top, the sRGB tag, refusals; and the
// auto exposure's log average over lit pixels.
#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "nimbus/render/image/image_io.hpp"
#include "support/vdb_fixtures.hpp"

namespace {

using nimbus::render::auto_exposure_stops;
using nimbus::render::Image;
using nimbus::render::PreviewOptions;
using nimbus::render::write_png_preview;
using nimbus::test::TempDir;
using Tonemap = PreviewOptions::Tonemap;

struct Decoded {
  int width = 0, height = 0;
  bool srgb_tagged = false;
  std::vector<std::uint8_t> rgb;
  const std::uint8_t* at(int x, int y) const { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
};

Decoded decode(const std::filesystem::path& file) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, file.c_str())) throw std::runtime_error(png.message);
  Decoded d;
  d.width = static_cast<int>(png.width);
  d.height = static_cast<int>(png.height);
  d.srgb_tagged = (png.flags & PNG_IMAGE_FLAG_COLORSPACE_NOT_sRGB) == 0;
  EXPECT_EQ(png.format, PNG_FORMAT_RGB) << "stored format (RGB, 8-bit, no alpha)";
  png.format = PNG_FORMAT_RGB;
  d.rgb.resize(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, d.rgb.data(), 0, nullptr)) throw std::runtime_error(png.message);
  return d;
}

Image grey(int w, int h, float v, float alpha = 1.0f) {
  Image im(w, h);
  for (int i = 0; i < w * h; ++i) {
    im.rgba[4 * i] = im.rgba[4 * i + 1] = im.rgba[4 * i + 2] = v;
    im.rgba[4 * i + 3] = alpha;
  }
  return im;
}

// The sRGB encoding (IEC 61966-2-1) of a linear value, as an 8-bit code.
int srgb8(double linear) {
  const double e = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
  return static_cast<int>(std::lround(255.0 * e));
}

int preview_grey(float value, PreviewOptions options) {
  TempDir dir;
  write_png_preview(dir / "p.png", grey(3, 2, value), options);
  const Decoded d = decode(dir / "p.png");
  EXPECT_EQ(d.at(0, 0)[0], d.at(2, 1)[2]);
  return d.at(1, 1)[1];
}

TEST(ImagePng, MiddleGreyIs118WithTheSrgbCurve) {
  // 0.18 linear -> 1.055 * 0.18^(1/2.4) - 0.055 = 0.4613 -> 117.6 -> 118 (not 0.18 * 255 = 46,
  // nor 0.18^(1/2.2) * 255 = 117.0 -> 117 with a plain gamma).
  EXPECT_EQ(preview_grey(0.18f, {0.0, Tonemap::Clamp}), 118);
  EXPECT_EQ(srgb8(0.18), 118);
  // The linear toe below 0.0031308: 0.002 -> 12.92 * 0.002 * 255 = 6.6 -> 7.
  EXPECT_EQ(preview_grey(0.002f, {0.0, Tonemap::Clamp}), 7);
  EXPECT_EQ(preview_grey(0.0f, {0.0, Tonemap::Clamp}), 0);
  EXPECT_EQ(preview_grey(1.0f, {0.0, Tonemap::Clamp}), 255);
  EXPECT_EQ(preview_grey(7.0f, {0.0, Tonemap::Clamp}), 255);
  for (const double v : {0.01, 0.05, 0.3, 0.5, 0.8}) {
    EXPECT_EQ(preview_grey(static_cast<float>(v), {0.0, Tonemap::Clamp}), srgb8(v)) << v;
  }
}

TEST(ImagePng, ExposureScalesByPowersOfTwo) {
  EXPECT_EQ(preview_grey(0.09f, {1.0, Tonemap::Clamp}), 118);
  EXPECT_EQ(preview_grey(0.72f, {-2.0, Tonemap::Clamp}), 118);
  EXPECT_EQ(preview_grey(0.18f / 1024.0f, {10.0, Tonemap::Clamp}), 118);
}

TEST(ImagePng, ToneCurvesHaveTheirDefiningValues) {
  // Reinhard c / (1 + c): 1 -> 0.5, 3 -> 0.75, 99 -> 0.99.
  EXPECT_EQ(preview_grey(1.0f, {0.0, Tonemap::Reinhard}), srgb8(0.5));
  EXPECT_EQ(preview_grey(3.0f, {0.0, Tonemap::Reinhard}), srgb8(0.75));
  EXPECT_EQ(preview_grey(99.0f, {0.0, Tonemap::Reinhard}), srgb8(0.99));
  // ACES fitted: black stays black, bright saturates to white, and it is monotone.
  EXPECT_EQ(preview_grey(0.0f, {0.0, Tonemap::AcesFitted}), 0);
  EXPECT_EQ(preview_grey(1000.0f, {0.0, Tonemap::AcesFitted}), 255);
  int last = 0;
  for (double v = 1e-3; v < 100.0; v *= 1.5) {
    const int code = preview_grey(static_cast<float>(v), {0.0, Tonemap::AcesFitted});
    EXPECT_GE(code, last) << v;
    last = code;
  }
  // On a grey both of the fit's matrices are the identity (their rows sum to 1), leaving the
  // rational curve f(x) = (x (x + 0.0245786) - 0.000090537) / (x (0.983729 x + 0.4329510) +
  // 0.238081): f(0.18) = 0.10559 -> sRGB 91, f(1) = 0.61912 -> 206.
  EXPECT_EQ(preview_grey(0.18f, {0.0, Tonemap::AcesFitted}), 91);
  EXPECT_EQ(preview_grey(1.0f, {0.0, Tonemap::AcesFitted}), 206);
}

// AgX, the default: values worked out by hand from its documented steps (image_png.cpp): on a
// grey the inset and outset rows sum to 1, so 0.18 -> log2 encoding 0.6061 -> sigmoid 0.4999
// -> 2.2 power 0.2175 -> sRGB 128; 1 -> 0.7560 -> 0.7951 -> 0.6038 -> 202; 0.01 -> 18.
TEST(ImagePng, AgxIsTheDefaultAndRunsBrightColoursToWhite) {
  EXPECT_EQ(PreviewOptions{}.tonemap, Tonemap::AgX);
  EXPECT_EQ(preview_grey(0.0f, {0.0, Tonemap::AgX}), 0);
  EXPECT_EQ(preview_grey(0.18f, {0.0, Tonemap::AgX}), 128);
  EXPECT_EQ(preview_grey(1.0f, {0.0, Tonemap::AgX}), 202);
  EXPECT_EQ(preview_grey(0.01f, {0.0, Tonemap::AgX}), 18);
  EXPECT_EQ(preview_grey(1000.0f, {0.0, Tonemap::AgX}), 255);
  int last = 0;
  for (double v = 1e-5; v < 100.0; v *= 1.3) {
    const int code = preview_grey(static_cast<float>(v), {0.0, Tonemap::AgX});
    EXPECT_GE(code, last) << v;
    last = code;
  }
  // A very bright pure red becomes white, as film does; a dim one stays red.
  const float bright[3] = {1000.0f, 0.0f, 0.0f}, dim[3] = {0.3f, 0.0f, 0.0f};
  const auto b = nimbus::render::preview_pixel(bright, {0.0, Tonemap::AgX});
  const auto d = nimbus::render::preview_pixel(dim, {0.0, Tonemap::AgX});
  EXPECT_GE(b[1], 250);
  EXPECT_GE(b[2], 250);
  EXPECT_GT(d[0], d[1] + 60);
}

TEST(ImagePng, RowZeroIsTheTopAndTheFileIsOpaqueSrgb) {
  TempDir dir;
  Image im(4, 3);
  for (int x = 0; x < 4; ++x) {
    im.pixel(x, 0)[0] = 1.0f;  // top row red
    im.pixel(x, 2)[2] = 1.0f;  // bottom row blue
    for (int y = 0; y < 3; ++y) im.pixel(x, y)[3] = 0.5f;  // alpha does not reach the preview
  }
  im.pixel(3, 1)[1] = 0.18f;  // premultiplied over black: the stored value
  write_png_preview(dir / "p.png", im, {0.0, Tonemap::Clamp});
  const Decoded d = decode(dir / "p.png");
  ASSERT_EQ(d.width, 4);
  ASSERT_EQ(d.height, 3);
  EXPECT_TRUE(d.srgb_tagged);
  EXPECT_EQ(d.at(0, 0)[0], 255);
  EXPECT_EQ(d.at(0, 0)[2], 0);
  EXPECT_EQ(d.at(1, 2)[2], 255);
  EXPECT_EQ(d.at(1, 2)[0], 0);
  EXPECT_EQ(d.at(3, 1)[1], 118);
  EXPECT_EQ(d.at(0, 1)[1], 0);
}

TEST(ImagePng, BadInputIsRefusedAndNothingIsWritten) {
  TempDir dir;
  Image im = grey(3, 3, 0.5f);
  im.pixel(1, 2)[2] = std::numeric_limits<float>::quiet_NaN();
  try {
    write_png_preview(dir / "p.png", im, {});
    ADD_FAILURE() << "NaN accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("pixel (1, 2) channel B"), std::string::npos) << e.what();
  }
  EXPECT_THROW(write_png_preview(dir / "p.png", grey(3, 3, 0.5f), {std::nan(""), Tonemap::Clamp}),
               std::invalid_argument);
  EXPECT_THROW(write_png_preview(dir / "p.png", Image(), {}), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir / "p.png"));
  nimbus::test::write_bytes(dir / "file", "x");
  EXPECT_THROW(write_png_preview(dir / "file" / "p.png", grey(3, 3, 0.5f), {}), std::runtime_error);
  EXPECT_EQ(nimbus::test::count_temp_files(dir.path), 0);
}

TEST(ImagePng, AutoExposureMapsTheLogAverageOfLitPixelsToMiddleGrey) {
  EXPECT_NEAR(auto_exposure_stops(grey(4, 4, 0.18f)), 0.0, 1e-6);
  EXPECT_NEAR(auto_exposure_stops(grey(4, 4, 1e-3f)), std::log2(180.0), 1e-5);
  // Log average of 0.01 and 0.04 is 0.02; the black half does not count.
  Image im(4, 2);
  for (int x = 0; x < 4; ++x) {
    const float v = x % 2 ? 0.04f : 0.01f;
    for (int c = 0; c < 3; ++c) im.pixel(x, 0)[c] = v;
  }
  EXPECT_NEAR(auto_exposure_stops(im), std::log2(0.18 / 0.02), 1e-5);
  // Luminance, not the mean of R, G and B: pure green 0.18 / 0.7152.
  Image green(2, 2);
  for (int i = 0; i < 4; ++i) green.rgba[4 * i + 1] = 0.18f / 0.7152f;
  EXPECT_NEAR(auto_exposure_stops(green), 0.0, 1e-5);
  EXPECT_EQ(auto_exposure_stops(grey(2, 2, 0.0f)), 0.0);
  // Used as the exposure, dim fog previews at middle grey.
  EXPECT_EQ(preview_grey(2e-4f, {auto_exposure_stops(grey(3, 2, 2e-4f)), Tonemap::Clamp}), 118);
}

}  // namespace
