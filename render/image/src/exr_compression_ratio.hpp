// How far each OpenEXR compression can expand its bytes: the bound read_exr puts on what a file's
// header may declare (exr_header_check.hpp). A sound bound, never a guess: a real file never
// exceeds it (OpenEXR also stores a chunk as it is when compressing would not make it smaller),
// so a header declaring more pixel data than the file's size times this declares pixels the file
// cannot hold.
#pragma once

namespace nimbus::render {

// OpenEXR's compression numbers (ImfCompression.h, the "compression" attribute's byte).
inline constexpr int kExrCompressions = 10;
inline constexpr const char* kExrCompressionNames[kExrCompressions] = {
    "NONE", "RLE", "ZIPS", "ZIP", "PIZ", "PXR24", "B44", "B44A", "DWAA", "DWAB"};

// Scan lines per chunk, the unit of the offset table (OpenEXR file layout; ImfCompressor.cpp,
// numLinesInBuffer).
inline constexpr int kExrLinesPerChunk[kExrCompressions] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};

// The most bytes of pixel data one byte of the file can decompress to:
inline constexpr double kExrMaxRatio[kExrCompressions] = {
    1,      // NONE: the bytes as they are.
    64,     // RLE: a count byte and a value byte give at most 128 bytes (ImfRle.cpp, rleUncompress).
    1032,   // ZIPS and ZIP: zlib's deflate reaches at most 1032:1, a 258-byte match coded in 2 bits
    1032,   //   (zlib.net/zlib_tech.html, "Maximum compression factor").
    454,    // PIZ: the wavelet keeps the size; its Huffman stage repeats a 16-bit value at most 255
            //   times per run code of at least 1 + 8 bits (ImfHuf.cpp, getCode): 255 * 16 / 9 < 454.
    1376,   // PXR24: FLOAT samples cut to 24 bits, then deflate: 4/3 * 1032.
    3,      // B44: a 4x4 block of HALF (32 bytes) in 14 bytes: 2.3 (other types stored as they are).
    11,     // B44A: a flat block in 3 bytes: 32/3.
    66048,  // DWAA and DWAB: the channels they run-length code go through RLE (64:1), then deflate
    66048,  //   (1032:1); the lossy DCT stage and the other channels reach less (ImfDwaCompressor.cpp).
};

}  // namespace nimbus::render
