// Image files: the linear half-float OpenEXR that every renderer writes (with its metadata) and
// a tone-mapped 8-bit sRGB PNG preview. Both are written atomically and refuse bad pixels.
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <string_view>

#include "nimbus/render/core/image.hpp"

namespace nimbus::render {

// Writes a scanline OpenEXR file: channels R, G, B, A as half floats (values above the half
// range, 65504, are clamped to it), ZIP compression, premultiplied alpha as stored. The header
// holds every Image::metadata entry as a string attribute, "nimbus_version", "comments" (unless
// metadata sets it) and the Rec. 709 chromaticities of the linear RGB. Refuses (before anything
// is written, std::invalid_argument) an image that check_image refuses and metadata names that
// EXR reserves ("channels", "compression", ...) or that are empty. Written atomically (a
// temporary file renamed into place); a failed write throws std::runtime_error naming `path`.
void write_exr(const std::filesystem::path& path, const Image& image);

// Reads any single-part scanline or tiled OpenEXR file into float RGBA (a missing alpha channel
// reads as 1, missing colour channels as 0), the top row of the data window first. Every string
// attribute of the header goes into Image::metadata, except those EXR reserves for its own use
// ("type", "name", ...: write_exr refuses them). The file is untrusted: a directory, FIFO, device
// or socket is refused before it is opened, and nothing is allocated from the header before it is
// checked against the file (src/exr_header_check.hpp): a data window of 1 to 2^28 pixels, at least
// one of R, G, B, A, no more pixel data than the file's size times the largest ratio its
// compression reaches (1032:1 for ZIP), attributes within the file, and memory for the image.
// Missing, corrupt or refused files throw std::runtime_error naming `path` in one line.
Image read_exr(const std::filesystem::path& path);

struct PreviewOptions {
  double exposure_stops = 0.0;  // radiance is multiplied by 2^exposure_stops before tone mapping
  // Clamp: min(c, 1). Reinhard: c / (1 + c) per channel (Reinhard et al. 2002, eq. 3).
  // AcesFitted: Stephen Hill's fit of the ACES RRT + sRGB ODT (BakingLab, 2016).
  // AgX: Troy Sobotka's AgX view transform (2022-23), the filmic default: a gamut inset, a log2
  // encoding of 16.5 stops around middle grey, a sigmoid, and the outset; bright saturated
  // colours run to white instead of skewing in hue, as film does (docs/clouds.md, "Output").
  enum class Tonemap { Clamp, Reinhard, AcesFitted, AgX } tonemap = Tonemap::AgX;
};

// Writes an opaque 8-bit RGB PNG: the premultiplied image composited over black (that is, its
// RGB as stored), exposed, tone mapped, encoded with the sRGB transfer curve (IEC 61966-2-1)
// and rounded to the nearest 8-bit code; the file is tagged sRGB. Row 0 is the top row. Refuses
// what check_image refuses and a non-finite exposure (std::invalid_argument); written atomically.
void write_png_preview(const std::filesystem::path& path, const Image& image,
                       const PreviewOptions& options = {});

// One pixel as write_png_preview encodes it (premultiplied RGB over black): the 8-bit sRGB codes.
// The viewer's display shader (shaders/lib/tonemap.glsl) computes the same.
std::array<std::uint8_t, 3> preview_pixel(const float rgb[3], const PreviewOptions& options = {});

// Exposure (in stops) that maps the log-average luminance of the covered pixels to middle grey
// 0.18 (Reinhard et al. 2002, eq. 1 with key a = 0.18): stops = log2(0.18 / L_avg) with
// L_avg = exp(mean(ln L)) over the pixels whose Rec. 709 luminance L = 0.2126 R + 0.7152 G +
// 0.0722 B is positive (black background would otherwise drag the average to zero). Dim fog of
// radiance 1e-3 thus gets about +7.5 stops. Returns 0 when no pixel is lit; clamped to +-40.
double auto_exposure_stops(const Image& image);

}  // namespace nimbus::render
