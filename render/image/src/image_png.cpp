// The tone-mapped 8-bit sRGB PNG preview (libpng's simplified write API) and auto exposure.
#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "nimbus/render/image/image_io.hpp"
#include "nimbus/base/atomic_file.hpp"

namespace nimbus::render {
namespace {

using Rgb = std::array<double, 3>;

// Stephen Hill's fit of the ACES reference rendering transform and sRGB output transform
// (BakingLab ACES.hlsl, 2016): linear sRGB -> ACES AP1-like space, the RRT+ODT rational fit,
// back to linear sRGB, clamped to [0, 1].
Rgb aces_fitted(const Rgb& c) {
  static constexpr double kIn[3][3] = {
      {0.59719, 0.35458, 0.04823}, {0.07600, 0.90834, 0.01566}, {0.02840, 0.13383, 0.83777}};
  static constexpr double kOut[3][3] = {
      {1.60475, -0.53108, -0.07367}, {-0.10208, 1.10813, -0.00605}, {-0.00327, -0.07276, 1.07602}};
  Rgb v{}, out{};
  for (int i = 0; i < 3; ++i) v[i] = kIn[i][0] * c[0] + kIn[i][1] * c[1] + kIn[i][2] * c[2];
  for (double& x : v) x = (x * (x + 0.0245786) - 0.000090537) / (x * (0.983729 * x + 0.4329510) + 0.238081);
  for (int i = 0; i < 3; ++i) {
    out[i] = std::clamp(kOut[i][0] * v[0] + kOut[i][1] * v[1] + kOut[i][2] * v[2], 0.0, 1.0);
  }
  return out;
}

// AgX in its widely used minimal form (the figures of Benjamin Wrensch's fit of Troy Sobotka's
// AgX, 2023; github.com/sobotka/AgX): the inset matrix pulls each primary a little towards the
// others, log2 of the result is mapped from [-12.47393, 4.026069] onto [0, 1] (0.18 lands at
// 0.606), a sixth-order polynomial fit of AgX's sigmoid gives the display value, the outset
// matrix undoes most of the inset, and the display's 2.2 power returns linear light for the sRGB
// encoding that follows. Each matrix row is divided by its sum (they sum to 1 within 2e-4), so a
// grey stays exactly grey. Middle grey comes out at a display value of 0.50.
Rgb agx(const Rgb& c) {
  static constexpr double kInset[3][3] = {{0.842479062253094, 0.0784335999999992, 0.0792237451477643},
                                          {0.0423282422610123, 0.878468636469772, 0.0791661274605434},
                                          {0.0423756549057051, 0.0784336, 0.879142973793104}};
  static constexpr double kOutset[3][3] = {{1.19687900512017, -0.0980208811401368, -0.0990297440797205},
                                           {-0.0528968517574562, 1.15190312990417, -0.0989611768448433},
                                           {-0.0529716355144438, -0.0980434501171241, 1.15107367264116}};
  constexpr double kMinEv = -12.47393, kMaxEv = 4.026069;
  Rgb v{}, w{}, out{};
  for (int i = 0; i < 3; ++i)
    v[i] = (kInset[i][0] * c[0] + kInset[i][1] * c[1] + kInset[i][2] * c[2]) / (kInset[i][0] + kInset[i][1] + kInset[i][2]);
  for (double& x : v) {
    const double e = std::clamp(std::log2(std::max(x, 1e-10)), kMinEv, kMaxEv);
    const double t = (e - kMinEv) / (kMaxEv - kMinEv);
    const double t2 = t * t, t4 = t2 * t2;
    x = 15.5 * t4 * t2 - 40.14 * t4 * t + 31.96 * t4 - 6.868 * t2 * t + 0.4298 * t2 + 0.1191 * t - 0.00232;
  }
  for (int i = 0; i < 3; ++i)
    w[i] = (kOutset[i][0] * v[0] + kOutset[i][1] * v[1] + kOutset[i][2] * v[2]) / (kOutset[i][0] + kOutset[i][1] + kOutset[i][2]);
  for (int i = 0; i < 3; ++i) out[i] = std::pow(std::clamp(w[i], 0.0, 1.0), 2.2);
  return out;
}

Rgb tonemap(Rgb c, PreviewOptions::Tonemap t) {
  switch (t) {
    case PreviewOptions::Tonemap::Clamp:
      for (double& x : c) x = std::min(x, 1.0);
      return c;
    case PreviewOptions::Tonemap::Reinhard:  // Reinhard et al. 2002, eq. 3, per channel
      for (double& x : c) x = x / (1.0 + x);
      return c;
    case PreviewOptions::Tonemap::AcesFitted:
      return aces_fitted(c);
    case PreviewOptions::Tonemap::AgX:
      return agx(c);
  }
  return c;
}

// The sRGB transfer function (IEC 61966-2-1) from linear [0, 1] to an 8-bit code.
std::uint8_t srgb8(double linear) {
  const double x = std::clamp(linear, 0.0, 1.0);
  const double e = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
  return static_cast<std::uint8_t>(std::lround(e * 255.0));
}

}  // namespace

std::array<std::uint8_t, 3> preview_pixel(const float rgb[3], const PreviewOptions& options) {
  const double scale = std::exp2(options.exposure_stops);
  const Rgb mapped = tonemap({rgb[0] * scale, rgb[1] * scale, rgb[2] * scale}, options.tonemap);
  return {srgb8(mapped[0]), srgb8(mapped[1]), srgb8(mapped[2])};
}

void write_png_preview(const std::filesystem::path& path, const Image& image, const PreviewOptions& options) {
  check_image(image, "PNG " + path.string());
  if (!std::isfinite(options.exposure_stops)) {
    throw std::invalid_argument("PNG preview: exposure_stops is not finite");
  }
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(image.width) * image.height * 3);
  for (std::size_t p = 0; p < rgb.size() / 3; ++p) {
    const float* px = image.rgba.data() + 4 * p;  // premultiplied: over black is the RGB itself
    const std::array<std::uint8_t, 3> code = preview_pixel(px, options);
    for (int c = 0; c < 3; ++c) rgb[3 * p + c] = code[c];
  }
  write_atomically(path, [&](const std::filesystem::path& tmp) {
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = static_cast<png_uint_32>(image.width);
    png.height = static_cast<png_uint_32>(image.height);
    png.format = PNG_FORMAT_RGB;  // 8-bit, non-linear: libpng tags the file sRGB
    const int ok = png_image_write_to_file(&png, tmp.c_str(), 0, rgb.data(), 3 * image.width, nullptr);
    const std::string message = png.message;
    png_image_free(&png);
    if (!ok) throw std::runtime_error("cannot write PNG " + path.string() + ": " + message);
  });
}

double auto_exposure_stops(const Image& image) {
  check_image(image, "auto exposure");
  double sum_log = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
    const double l = 0.2126 * image.rgba[i] + 0.7152 * image.rgba[i + 1] + 0.0722 * image.rgba[i + 2];
    if (l > 0.0) {
      sum_log += std::log(l);
      ++n;
    }
  }
  if (n == 0) return 0.0;
  const double log_average = std::exp(sum_log / static_cast<double>(n));  // Reinhard 2002, eq. 1
  return std::clamp(std::log2(0.18 / log_average), -40.0, 40.0);
}

}  // namespace nimbus::render
