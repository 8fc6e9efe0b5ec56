// Reading a coverage map from a PNG (coverage_map.hpp). The file is untrusted: it is read whole as
// a regular file of bounded size (a FIFO or device is refused before it is opened), its header is
// checked against the file's size and the memory before any pixel buffer is allocated, and
// libpng's simplified API (png_image) does the decoding, so no setjmp/longjmp crosses this code;
// its errors come back in image.message.
#include <png.h>

#include <cstring>
#include <stdexcept>

#include "nimbus/base/input_limits.hpp"
#include "nimbus/base/memory.hpp"
#include "nimbus/volume/coverage_map.hpp"

namespace nimbus::volume {
namespace {

// 64 Mi pixels of 16-bit RGBA compress to at most about this much in a sane file.
constexpr std::uintmax_t kMaxCoveragePngBytes = std::uintmax_t(512) << 20;

// The most bytes of image data one byte of a PNG can hold: its pixels are one zlib stream, and
// deflate reaches at most 1032:1, a 258-byte match coded in 2 bits (zlib.net/zlib_tech.html,
// "Maximum compression factor"). A sound bound: no real file exceeds it.
constexpr std::uint64_t kDeflateMaxRatio = 1032;

// Bits a pixel takes in the image data, from the IHDR chunk (PNG specification, 11.2.2: the bit
// depth at byte 24 of the file, the colour type at byte 25); 0 when they are not there.
int bits_per_pixel(const std::string& png) {
  if (png.size() < 26 || png.compare(12, 4, "IHDR") != 0) return 0;
  const int depth = static_cast<unsigned char>(png[24]);
  switch (static_cast<unsigned char>(png[25])) {
    case 0: return depth;      // grey
    case 2: return 3 * depth;  // RGB
    case 3: return depth;      // palette index
    case 4: return 2 * depth;  // grey and alpha
    case 6: return 4 * depth;  // RGBA
    default: return 0;
  }
}

std::string size_text(std::uint64_t bytes) {
  if (bytes < 1024) return std::to_string(bytes) + " bytes";
  if (bytes < (std::uint64_t(1) << 20)) return std::to_string(bytes >> 10) + " KiB";
  return std::to_string(bytes >> 20) + " MiB";
}

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
  // The image data the header declares, at least w * h pixels of their bits (the filter bytes
  // come on top), must fit in the file's compressed bytes: a file of a few KB that declares
  // 8192 x 8192 pixels cannot hold them, and is refused before 448 MB are allocated for them.
  const int bits = bits_per_pixel(bytes);
  if (bits == 0) throw std::runtime_error(where + ": its IHDR chunk is not where a PNG has it");
  const std::uint64_t data_bytes = (std::uint64_t(w) * std::uint64_t(h) * std::uint64_t(bits) + 7) / 8;
  if (data_bytes > kDeflateMaxRatio * bytes.size())
    throw std::runtime_error(where + ": its header declares " + std::to_string(w) + " x " + std::to_string(h) +
                             " pixels of " + std::to_string(bits) + " bits (" + size_text(data_bytes) +
                             ") in a file of " + size_text(bytes.size()) +
                             ", more than deflate compression can hold (at most 1032:1)");
  // The values as stored: 16-bit files through libpng's linear 16-bit format, 8-bit ones through
  // its 8-bit format (neither converts unless the file has a gamma chunk). Grey expands to red =
  // green = blue; alpha, if any, is composited onto black (a transparent pixel holds no cloud).
  const bool sixteen = (image.format & PNG_FORMAT_FLAG_LINEAR) != 0;
  image.format = sixteen ? PNG_FORMAT_LINEAR_RGB : PNG_FORMAT_RGB;
  const size_t n = size_t(w) * size_t(h) * 3;
  try {  // the values and the decoded pixels, before either is allocated
    ensure_fits_in_memory(uint64_t(w) * uint64_t(h), sizeof(float) + 3 * (sixteen ? 2 : 1),
                          where + ": " + std::to_string(w) + " x " + std::to_string(h) + " pixels");
  } catch (const OutOfMemoryRequest& e) {
    throw std::runtime_error(e.what());  // the file's doing, as every other refusal here
  }
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
