// Reading a coverage map from a PNG (coverage_map.hpp). The file is untrusted: it is read whole as
// a regular file of bounded size, its header is checked before any pixel buffer is allocated, and
// libpng's simplified API (png_image) does the decoding, so no setjmp/longjmp crosses this code;
// its errors come back in image.message.
#include <png.h>

#include <cstring>
#include <stdexcept>

#include "nimbus/base/input_limits.hpp"
#include "nimbus/volume/coverage_map.hpp"

namespace nimbus::volume {
namespace {

// 64 Mi pixels of 16-bit RGBA compress to at most about this much in a sane file.
constexpr std::uintmax_t kMaxCoveragePngBytes = std::uintmax_t(512) << 20;

struct ImageGuard {
  png_image* image;
  ~ImageGuard() { png_image_free(image); }
};

}  // namespace

std::shared_ptr<const CoverageImage> read_coverage_png(const std::string& path) {
  const std::string where = "coverage map '" + echo(path, 300) + "'";
  const std::string bytes = read_regular_file(path, where, kMaxCoveragePngBytes);  // runtime_error naming it
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  ImageGuard guard{&image};
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size()))
    throw std::runtime_error(where + ": not a readable PNG (" + image.message + ")");
  const int64_t w = image.width, h = image.height;
  if (w < 1 || h < 1 || w > kMaxCoverageMapSide || h > kMaxCoverageMapSide || w * h > kMaxCoverageMapPixels)
    throw std::runtime_error(where + ": " + std::to_string(w) + " x " + std::to_string(h) +
                             " pixels; a coverage map is at most " + std::to_string(kMaxCoverageMapSide) + " a side and " +
                             std::to_string(kMaxCoverageMapPixels >> 20) + " Mi pixels");
  // The values as stored: 16-bit files through libpng's linear 16-bit format, 8-bit ones through
  // its 8-bit format (neither converts unless the file has a gamma chunk). Grey expands to red =
  // green = blue; alpha, if any, is composited onto black (a transparent pixel holds no cloud).
  const bool sixteen = (image.format & PNG_FORMAT_FLAG_LINEAR) != 0;
  image.format = sixteen ? PNG_FORMAT_LINEAR_RGB : PNG_FORMAT_RGB;
  const size_t n = size_t(w) * size_t(h) * 3;
  std::vector<float> values(size_t(w) * size_t(h));
  if (sixteen) {
    std::vector<png_uint_16> px(n);
    if (!png_image_finish_read(&image, nullptr, px.data(), 0, nullptr))
      throw std::runtime_error(where + ": damaged PNG (" + image.message + ")");
    for (size_t i = 0; i < values.size(); ++i) values[i] = float(px[3 * i]) / 65535.0f;
  } else {
    const png_color black{0, 0, 0};
    std::vector<png_byte> px(n);
    if (!png_image_finish_read(&image, &black, px.data(), 0, nullptr))
      throw std::runtime_error(where + ": damaged PNG (" + image.message + ")");
    for (size_t i = 0; i < values.size(); ++i) values[i] = float(px[3 * i]) / 255.0f;
  }
  auto out = std::make_shared<CoverageImage>();
  out->width = int(w);
  out->height = int(h);
  out->value = std::move(values);
  out->source = path;
  return out;
}

}  // namespace nimbus::volume
