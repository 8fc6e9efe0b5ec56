// OpenEXR writing and reading (half-float RGBA, ZIP, string metadata), through OpenEXR 3.1. Reading
// goes through ExrInputStream (regular files only) and check_exr_header (what the header declares,
// against the file and memory) before OpenEXR or nimbus allocate anything from the header.
#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "exr_header_check.hpp"
#include "exr_input_stream.hpp"
#include "nimbus/base/atomic_file.hpp"
#include "nimbus/base/input_limits.hpp"
#include "nimbus/render/image/image_io.hpp"

#ifndef NIMBUS_VERSION
#define NIMBUS_VERSION "unknown"
#endif

namespace nimbus::render {
namespace {

constexpr float kHalfMax = 65504.0f;  // largest finite half float
constexpr std::array<const char*, 4> kChannels{"R", "G", "B", "A"};
// Attribute names with a meaning for EXR readers beyond those every header already holds
// (multi-part, tiled and deep files); a string under these names would confuse them.
constexpr std::array<const char*, 7> kReserved{"type", "name", "version", "chunkCount", "tiles",
                                               "maxSamplesPerPixel", "view"};
constexpr std::size_t kMaxAttributeName = 255;  // OpenEXR 2+ long attribute names

bool is_reserved(const std::string& name) {
  return std::find_if(kReserved.begin(), kReserved.end(), [&](const char* r) { return name == r; }) !=
         kReserved.end();
}

Imf::Header make_header(const Image& image) {
  Imf::Header header(image.width, image.height);
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const char* c : kChannels) header.channels().insert(c, Imf::Channel(Imf::HALF));
  Imf::addChromaticities(header, Imf::Chromaticities());  // Rec. 709 primaries, D65
  for (const auto& [key, value] : image.metadata) {
    if (key.empty()) throw std::invalid_argument("EXR metadata: empty attribute name");
    if (key.size() > kMaxAttributeName) {
      throw std::invalid_argument("EXR metadata: attribute name longer than 255 characters: " + key.substr(0, 40) +
                                  "...");
    }
    const bool reserved = is_reserved(key);
    const auto existing = header.find(key);
    if (reserved || (existing != header.end() && !dynamic_cast<const Imf::StringAttribute*>(&existing.attribute()))) {
      throw std::invalid_argument("EXR metadata: attribute name '" + key + "' is reserved by OpenEXR");
    }
    header.insert(key, Imf::StringAttribute(value));
  }
  header.insert("nimbus_version", Imf::StringAttribute(NIMBUS_VERSION));
  if (!image.metadata.count("comments")) {
    Imf::addComments(header, std::string("linear Rec. 709 RGB radiance (W sr^-1 m^-2), premultiplied alpha; "
                                         "written by nimbus ") + NIMBUS_VERSION);
  }
  return header;
}

}  // namespace

void write_exr(const std::filesystem::path& path, const Image& image) {
  check_image(image, "EXR " + path.string());
  const Imf::Header header = make_header(image);
  std::vector<half> data(image.rgba.size());
  std::transform(image.rgba.begin(), image.rgba.end(), data.begin(),
                 [](float v) { return half(std::min(v, kHalfMax)); });
  write_atomically(path, [&](const std::filesystem::path& tmp) {
    try {
      Imf::OutputFile file(tmp.c_str(), header);
      Imf::FrameBuffer fb;
      const std::size_t xs = 4 * sizeof(half);
      const std::size_t ys = xs * image.width;
      for (std::size_t c = 0; c < 4; ++c) {
        fb.insert(kChannels[c], Imf::Slice(Imf::HALF, reinterpret_cast<char*>(data.data() + c), xs, ys));
      }
      file.setFrameBuffer(fb);
      file.writePixels(image.height);
    } catch (const std::exception& e) {
      throw std::runtime_error("cannot write EXR " + path.string() + ": " + e.what());
    }
  });
}

Image read_exr(const std::filesystem::path& path) {
  // A directory, FIFO, device or socket is refused before it is opened: a FIFO would block the
  // open, a device feed the reader without end.
  refuse_special_file(path.string(), "cannot read EXR");
  const std::string name = echo(path.string(), 300);
  try {
    ExrInputStream stream(path.string());
    const ExrWindow checked = check_exr_header(stream);  // before anything is allocated from the header
    Imf::InputFile file(stream);
    const Imath::Box2i dw = file.header().dataWindow();
    if (dw.min.x != checked.x_min || dw.min.y != checked.y_min || dw.max.x != checked.x_max ||
        dw.max.y != checked.y_max)
      throw std::runtime_error("OpenEXR read another data window than the header check did");
    Image image(dw.max.x - dw.min.x + 1, dw.max.y - dw.min.y + 1);
    Imf::FrameBuffer fb;
    const std::size_t xs = 4 * sizeof(float);
    const std::size_t ys = xs * image.width;
    for (std::size_t c = 0; c < 4; ++c) {
      fb.insert(kChannels[c], Imf::Slice::Make(Imf::FLOAT, image.rgba.data() + c, dw, xs, ys, 1, 1,
                                               c == 3 ? 1.0 : 0.0));
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    for (auto it = file.header().begin(); it != file.header().end(); ++it) {
      const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute());
      if (s && !is_reserved(it.name())) {
        image.metadata[it.name()] = s->value();
      }
    }
    return image;
  } catch (const std::exception& e) {
    // OpenEXR's messages may span lines and quote the file's bytes: one bounded line.
    throw std::runtime_error("cannot read EXR " + name + ": " + echo(e.what(), 1000));
  }
}

}  // namespace nimbus::render
