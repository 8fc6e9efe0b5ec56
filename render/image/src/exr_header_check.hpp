// What an EXR file's header declares, checked against the file itself before OpenEXR or nimbus
// allocate anything from it: before this check, a 4 KB file declaring 8192 x 8192 pixels made
// read_exr take 1.1 GB, and 16384 x 16384 asked for 4 GiB.
#pragma once
#include <cstdint>

#include "exr_input_stream.hpp"

namespace nimbus::render {

// read_exr's largest data window: 2^28 pixels (4 GiB as float RGBA); a larger one is taken as
// corruption.
inline constexpr std::uint64_t kMaxExrPixels = std::uint64_t{1} << 28;

// Walks the header of every part (OpenEXR file layout: magic number, version field, attributes
// of name, type name, size and value, a 0 byte after each header) with the file's own size, and
// throws std::runtime_error saying what is wrong, without the file's name (read_exr adds it),
// unless:
// - the file starts with EXR's magic number and version 2, is not deep, and every attribute's
//   value lies within the file;
// - each part declares a data window of 1 to kMaxExrPixels pixels, a known compression, channels
//   of known pixel types sampled at least 1:1, and at least one of R, G, B, A (the channels
//   read_exr reads) at full resolution;
// - its chunk offset table fits in the file (8 bytes a chunk);
// - its pixel data, as decompressed, is at most the file's size times the largest ratio its
//   compression can reach (exr_compression_ratio.hpp);
// - the float RGBA image and OpenEXR's buffers for it fit in memory (ensure_fits_in_memory; its
//   OutOfMemoryRequest is let through).
// Returns the first part's data window, the one read_exr reads.
struct ExrWindow {
  std::int32_t x_min, y_min, x_max, y_max;
};
ExrWindow check_exr_header(const ExrInputStream& in);

}  // namespace nimbus::render
