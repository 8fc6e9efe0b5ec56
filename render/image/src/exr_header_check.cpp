// Checking what an EXR header declares against the file (exr_header_check.hpp). The walk follows
// OpenEXR 3.1's own reading of a header (Header::readFrom and each attribute's readValueFrom), so
// that it sees the attributes OpenEXR will see: most known types read a fixed number of bytes
// whatever their size field says, and a channel list reads until its empty name.
#include "exr_header_check.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "exr_compression_ratio.hpp"
#include "nimbus/base/input_limits.hpp"
#include "nimbus/base/memory.hpp"

namespace nimbus::render {
namespace {

constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();

std::uint64_t mul(std::uint64_t a, std::uint64_t b) { return a != 0 && b > kMax / a ? kMax : a * b; }
std::uint64_t add(std::uint64_t a, std::uint64_t b) { return b > kMax - a ? kMax : a + b; }

// "312 bytes", "4.0 KiB", "1.0 GiB".
std::string size_text(std::uint64_t bytes) {
  if (bytes < 1024) return std::to_string(bytes) + " bytes";
  const char* units[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  double v = double(bytes) / 1024.0;
  int u = 0;
  while (v >= 1024.0 && u < 5) v /= 1024.0, ++u;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f %s", v, units[u]);
  return buf;
}

[[noreturn]] void refuse(const std::string& what) { throw std::runtime_error(what); }

// The file's bytes from a position on, read through a 64 KiB window; every read is checked
// against the file's end.
class Cursor {
 public:
  explicit Cursor(const ExrInputStream& in) : in_(in) {}
  std::uint64_t pos() const { return pos_; }
  std::uint64_t left() const { return pos_ < in_.size() ? in_.size() - pos_ : 0; }

  unsigned char byte(const char* what) {
    if (pos_ < start_ || pos_ >= start_ + buf_.size()) {
      if (left() == 0) ends_inside(what);
      buf_.resize(std::size_t(std::min<std::uint64_t>(left(), 65536)));
      buf_.resize(in_.read_at(pos_, buf_.data(), buf_.size()));
      start_ = pos_;
      if (buf_.empty()) ends_inside(what);
    }
    return static_cast<unsigned char>(buf_[std::size_t(pos_++ - start_)]);
  }
  std::uint32_t u32(const char* what) {  // little-endian, as EXR stores every number (ImfXdr.h)
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= std::uint32_t(byte(what)) << (8 * i);
    return v;
  }
  std::int32_t i32(const char* what) { return static_cast<std::int32_t>(u32(what)); }
  unsigned char peek(const char* what) {
    const unsigned char b = byte(what);
    --pos_;
    return b;
  }
  // A name: up to 255 bytes and a 0 byte (Name::MAX_LENGTH in ImfName.h).
  std::string name(const char* what) {
    std::string s;
    for (unsigned char c; (c = byte(what)) != 0;) {
      if (s.size() == 255)
        refuse(std::string("its header holds ") + what + " longer than 255 bytes ('" + echo(s) + "')");
      s += char(c);
    }
    return s;
  }
  void skip(std::uint64_t n, const std::string& what) {
    if (n > left())
      refuse("its " + what + " of " + size_text(n) + " reaches beyond the end of the file (" + size_text(in_.size()) +
             ")");
    pos_ += n;
  }

 private:
  [[noreturn]] void ends_inside(const char* what) {
    refuse(std::string("the file ends inside its header (in ") + what + ", at byte " + std::to_string(pos_) + ")");
  }
  const ExrInputStream& in_;
  std::uint64_t pos_ = 0;
  std::uint64_t start_ = 0;
  std::vector<char> buf_;
};

struct Channel {
  int type = 0;  // 0 UINT, 1 HALF, 2 FLOAT (ImfPixelType.h)
  std::int32_t x_sampling = 1, y_sampling = 1;
};

// What read_exr needs from one header.
struct Part {
  std::optional<std::array<std::int32_t, 4>> data_window;  // xMin, yMin, xMax, yMax
  int compression = 3;  // Header()'s default, ZIP, when the attribute is missing
  std::map<std::string, Channel> channels;
  std::optional<std::array<std::uint32_t, 2>> tiles;
  int level_mode = 0;
  std::optional<std::string> type;
  std::optional<std::int32_t> chunk_count;
};

// Bytes each known attribute type reads whatever its size field says (ImfHeader.cpp,
// staticInitialize, and the types' readValueFrom); 0: its size field, or its own rule below.
std::uint64_t fixed_size(const std::string& type) {
  static const std::map<std::string, std::uint64_t> sizes = {
      {"box2i", 16}, {"box2f", 16}, {"chromaticities", 32}, {"compression", 1}, {"deepImageState", 1},
      {"double", 8}, {"envmap", 1}, {"float", 4},           {"int", 4},         {"keycode", 28},
      {"lineOrder", 1}, {"m33f", 36}, {"m33d", 72},         {"m44f", 64},       {"m44d", 128},
      {"rational", 8}, {"tiledesc", 9}, {"timecode", 8},    {"v2i", 8},         {"v2f", 8},
      {"v2d", 16},   {"v3i", 12},   {"v3f", 12},            {"v3d", 24}};
  const auto it = sizes.find(type);
  return it == sizes.end() ? 0 : it->second;
}

// A channel list adds to the channels read so far, a name read again replacing its channel
// (ChannelListAttribute::readValueFrom and ChannelList::insert).
void read_channels(Cursor& c, Part& part) {
  for (std::string name; !(name = c.name("a channel name")).empty();) {
    Channel ch;
    ch.type = c.i32("a channel");
    c.skip(4, "channel '" + echo(name) + "'");  // pLinear and three reserved bytes
    ch.x_sampling = c.i32("a channel");
    ch.y_sampling = c.i32("a channel");
    part.channels[name] = ch;
  }
}

// One header, from its first attribute to its 0 byte.
Part read_header(Cursor& c) {
  Part part;
  for (std::string name; !(name = c.name("an attribute name")).empty();) {
    const std::string type = c.name("an attribute type name");
    const std::int32_t size = c.i32("an attribute size");
    const std::string what = "attribute '" + echo(name) + "' (" + echo(type) + ")";
    if (size < 0) refuse("its " + what + " has a negative size (" + std::to_string(size) + ")");
    const std::uint64_t start = c.pos();
    if (name == "dataWindow" && type == "box2i") {
      part.data_window = std::array<std::int32_t, 4>{c.i32("dataWindow"), c.i32("dataWindow"), c.i32("dataWindow"),
                                                     c.i32("dataWindow")};
    } else if (name == "compression" && type == "compression") {
      part.compression = c.byte("compression");
    } else if (name == "channels" && type == "chlist") {
      read_channels(c, part);
    } else if (name == "tiles" && type == "tiledesc") {
      part.tiles = std::array<std::uint32_t, 2>{c.u32("tiles"), c.u32("tiles")};
      part.level_mode = c.byte("tiles") & 0x0f;
    } else if (name == "chunkCount" && type == "int") {
      part.chunk_count = c.i32("chunkCount");
    } else if (name == "type" && type == "string") {
      std::string value;
      if (size <= 64) {
        for (std::int32_t i = 0; i < size; ++i) value += char(c.byte("type"));
      } else {
        c.skip(std::uint64_t(size), what);
      }
      part.type = value;
    } else if (type == "chlist") {
      Part ignored;
      read_channels(c, ignored);
    }
    const std::uint64_t read = c.pos() - start;
    // What OpenEXR reads of this attribute: a fixed size, its own rule, or its size field
    // (strings, string and float vectors, previews, and types it does not know, kept opaque).
    std::uint64_t length = std::uint64_t(size);
    if (const std::uint64_t fixed = fixed_size(type)) length = fixed;
    if (type == "chlist") length = read;
    if (type == "floatvector") length = std::uint64_t(size) / 4 * 4;
    if (type == "idmanifest") {  // reads an 8-byte size, then size - 4 bytes (ImfIDManifestAttribute.cpp)
      if (size < 4) refuse("its " + what + " is shorter than 4 bytes");
      length = std::uint64_t(size) + 4;
    }
    if (length > read) c.skip(length - read, what);
  }
  return part;
}

const char* channel_type_name(int type) { return type == 0 ? "UINT" : type == 1 ? "HALF" : "FLOAT"; }

void check_part(const Part& part, bool tiled, std::uint64_t file_size) {
  if (!part.data_window) refuse("its header has no dataWindow (box2i)");
  const auto& dw = *part.data_window;
  const std::int64_t w = std::int64_t(dw[2]) - dw[0] + 1, h = std::int64_t(dw[3]) - dw[1] + 1;
  const std::string window = std::to_string(w) + "x" + std::to_string(h);
  if (w < 1 || h < 1)
    refuse("its data window (" + std::to_string(dw[0]) + ", " + std::to_string(dw[1]) + ") - (" +
           std::to_string(dw[2]) + ", " + std::to_string(dw[3]) + ") holds no pixel");
  const std::uint64_t pixels = std::uint64_t(w) * std::uint64_t(h);  // < 2^64: each side < 2^32
  if (pixels > kMaxExrPixels)
    refuse("its data window of " + window + " pixels is larger than nimbus reads (" + std::to_string(kMaxExrPixels) +
           " pixels)");
  if (part.compression < 0 || part.compression >= kExrCompressions)
    refuse("its compression " + std::to_string(part.compression) + " is not one OpenEXR knows");
  const char* compression = kExrCompressionNames[part.compression];

  // The channels: bytes a pixel takes in OpenEXR's buffers, and the decompressed pixel data.
  std::uint64_t pixel_bytes = 0, data_bytes = 0;
  bool rgba = false;
  std::string names;
  for (const auto& [name, ch] : part.channels) {
    if (ch.type < 0 || ch.type > 2)
      refuse("its channel '" + echo(name) + "' has pixel type " + std::to_string(ch.type) + ", not one OpenEXR knows");
    if (ch.x_sampling < 1 || ch.y_sampling < 1)
      refuse("its channel '" + echo(name) + "' is sampled " + std::to_string(ch.x_sampling) + "x" +
             std::to_string(ch.y_sampling));
    const bool read = name == "R" || name == "G" || name == "B" || name == "A";
    if (read && (ch.x_sampling != 1 || ch.y_sampling != 1))
      refuse("its channel " + name + " is subsampled " + std::to_string(ch.x_sampling) + "x" +
             std::to_string(ch.y_sampling) + "; nimbus reads R, G, B and A at full resolution");
    rgba = rgba || read;
    const std::uint64_t bytes = ch.type == 1 ? 2 : 4;
    pixel_bytes = add(pixel_bytes, bytes);
    data_bytes = add(data_bytes, mul(mul(std::uint64_t(w / ch.x_sampling), std::uint64_t(h / ch.y_sampling)), bytes));
    if (names.size() < 80) names += (names.empty() ? "" : ", ") + echo(name) + " (" + channel_type_name(ch.type) + ")";
  }
  if (!rgba)
    refuse("it holds none of the channels R, G, B, A that nimbus reads (its channels: " +
           (names.empty() ? std::string("none") : names) + ")");

  // The chunk offset table: 8 bytes a chunk, all in the file (at least the level-0 tiles of a
  // tiled part; mipmap and ripmap levels add more).
  std::uint64_t chunks = 0;
  if (tiled) {
    if (!part.tiles) refuse("it is tiled but its header has no tiles (tiledesc)");
    const auto [tx, ty] = *part.tiles;
    if (tx < 1 || ty < 1 || tx > std::uint32_t(std::numeric_limits<std::int32_t>::max()) ||
        ty > std::uint32_t(std::numeric_limits<std::int32_t>::max()))
      refuse("its tiles of " + std::to_string(tx) + "x" + std::to_string(ty) + " pixels are not a tile size");
    if (part.level_mode > 2)
      refuse("its tiles' level mode " + std::to_string(part.level_mode) + " is not one OpenEXR knows");
    chunks = mul((std::uint64_t(w) + tx - 1) / tx, (std::uint64_t(h) + ty - 1) / ty);
  } else {
    const std::uint64_t lines = std::uint64_t(kExrLinesPerChunk[part.compression]);
    chunks = (std::uint64_t(h) + lines - 1) / lines;
  }
  if (part.chunk_count) {
    if (*part.chunk_count < 0) refuse("its chunkCount is negative (" + std::to_string(*part.chunk_count) + ")");
    chunks = std::max(chunks, std::uint64_t(*part.chunk_count));
  }
  if (mul(chunks, 8) > file_size)
    refuse("its header declares " + std::to_string(chunks) + " chunks of pixels, whose offsets alone (" +
           size_text(mul(chunks, 8)) + ") are more than the whole file (" + size_text(file_size) + ")");

  // The pixel data the chunks decompress to, against what the compression can pack in the file.
  const double ratio = kExrMaxRatio[part.compression];
  if (static_cast<long double>(data_bytes) > static_cast<long double>(ratio) * static_cast<long double>(file_size))
    refuse("its header declares " + window + " pixels (" + size_text(mul(pixels, 16)) +
           " as float RGBA) in a file of " + size_text(file_size) + ": their " + size_text(data_bytes) +
           " of channel data is more than " + compression + " compression can hold in it (at most " +
           std::to_string(int(ratio)) + ":1)");

  // Memory: the float RGBA image, and OpenEXR's buffers for one chunk and its compressor (for a
  // tiled part, a tile each and a row of tiles; ImfInputFile.cpp, ImfTiledInputFile.cpp).
  std::uint64_t bytes = mul(pixels, 16);
  if (tiled) {
    const auto [tx, ty] = *part.tiles;
    bytes = add(bytes, mul(mul(mul(tx, ty), pixel_bytes), 2));
    bytes = add(bytes, mul(mul(std::uint64_t(w), ty), pixel_bytes));
  } else {
    const std::uint64_t lines = std::uint64_t(kExrLinesPerChunk[part.compression]);
    bytes = add(bytes, mul(mul(mul(lines, std::uint64_t(w)), pixel_bytes), 2));
  }
  ensure_fits_in_memory(bytes, 1, "reading its data window of " + window + " pixels");
}

ExrWindow window_of(const Part& part) {
  const auto& dw = *part.data_window;  // check_part refused a part without one
  return {dw[0], dw[1], dw[2], dw[3]};
}

}  // namespace

ExrWindow check_exr_header(const ExrInputStream& in) {
  Cursor c(in);
  const std::uint32_t magic = c.u32("the magic number");
  if (magic != 20000630u) refuse("it is not an OpenEXR file (its first bytes are not EXR's magic number)");
  const std::uint32_t version = c.u32("the version field");
  if ((version & 0xff) != 2) refuse("its EXR version is " + std::to_string(version & 0xff) + ", not 2");
  const bool multi_part = (version & 0x1000) != 0;  // ImfVersion.h: MULTI_PART_FILE_FLAG
  if (!multi_part && (version & 0x800) != 0)        // NON_IMAGE_FLAG
    refuse("it holds deep data, which nimbus does not read");
  if (!multi_part) {
    const Part part = read_header(c);
    check_part(part, (version & 0x200) != 0, in.size());  // TILED_FLAG
    return window_of(part);
  }
  // A multi-part file: headers one after the other, an empty header after the last. read_exr
  // reads the first part, but OpenEXR reads every header and sets up every part's offsets.
  std::optional<ExrWindow> first;
  for (;;) {
    const Part part = read_header(c);
    if (!part.type) refuse("a part of this multi-part file has no type");
    if (*part.type == "deepscanline" || *part.type == "deeptile")
      refuse("it holds deep data, which nimbus does not read");
    if (*part.type != "scanlineimage" && *part.type != "tiledimage")
      refuse("a part of this multi-part file has the type '" + echo(*part.type) + "'");
    check_part(part, *part.type == "tiledimage", in.size());
    if (!first) first = window_of(part);
    if (c.peek("the end of the headers") == 0) return *first;
  }
}

}  // namespace nimbus::render
