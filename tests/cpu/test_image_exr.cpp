// EXR files: a round trip within half precision with the metadata, a header that an independent
// tool (OpenEXR's exrheader) reads as ZIP with our attributes, refusals of bad pixels and names
// before anything is written, and clear errors for unwritable, missing and corrupt files; hostile
// files (a FIFO, a header declaring more than the file holds) refused before opening or allocating.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>

#include "nimbus/base/memory.hpp"
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

// Hostile files: what is not a regular file is refused without being read, and a header cannot
// make the reader allocate more than the file can hold.

// The value of attribute `name` (whose type is `type`) in an EXR's bytes: its offset after the
// name, the type name and the 4-byte size (OpenEXR file layout).
std::size_t attribute_value(const std::string& exr, const std::string& name, const std::string& type) {
  const std::string key = name + '\0' + type + '\0';
  const std::size_t at = exr.find(key);
  if (at == std::string::npos) {
    ADD_FAILURE() << "no attribute " << name;
    return 0;
  }
  return at + key.size() + 4;
}

void put_i32(std::string& bytes, std::size_t at, std::int32_t v) {
  for (int i = 0; i < 4; ++i) bytes[at + i] = char((std::uint32_t(v) >> (8 * i)) & 0xff);  // little-endian
}

// A small valid file written by write_exr, with its dataWindow patched to (0, 0) - (x_max, y_max).
std::string with_data_window(const std::filesystem::path& written, std::int32_t x_max, std::int32_t y_max) {
  std::string bytes = nimbus::test::read_bytes(written);
  const std::size_t at = attribute_value(bytes, "dataWindow", "box2i");
  put_i32(bytes, at + 8, x_max);
  put_i32(bytes, at + 12, y_max);
  return bytes;
}

constexpr std::uint64_t kMiB = std::uint64_t(1) << 20;

TEST(ImageExrHostile, AFifoIsRefusedWithoutReadingFromIt) {
  TempDir dir;
  const auto fifo = dir / "f.exr";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // The test holds the FIFO open for writing with bytes in it: a reader that opened it would not
  // block (the test would hang instead of failing) but take the bytes, which must stay there.
  const int fd = ::open(fifo.c_str(), O_RDWR | O_NONBLOCK);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::write(fd, "not an EXR file", 15), 15);
  expect_error<std::runtime_error>([&] { read_exr(fifo); }, {fifo.string(), "is a FIFO"});
  char buf[32];
  EXPECT_EQ(::read(fd, buf, sizeof buf), 15) << "the reader took bytes from the FIFO";
  ::close(fd);
}

TEST(ImageExrHostile, DirectoriesAndDevicesAreRefusedByKind) {
  TempDir dir;
  std::filesystem::create_directory(dir / "d.exr");
  expect_error<std::runtime_error>([&] { read_exr(dir / "d.exr"); }, {(dir / "d.exr").string(), "is a directory"});
  expect_error<std::runtime_error>([&] { read_exr("/dev/zero"); }, {"/dev/zero", "is a character device"});
}

TEST(ImageExrHostile, AHeaderDeclaringMorePixelsThanTheFileHoldsIsRefusedBeforeAllocating) {
  TempDir dir;
  write_exr(dir / "small.exr", Image(8, 8));
  // 4096 x 4096 pixels (256 MiB as float RGBA, 128 MiB of half RGBA data) in a file of under
  // 8 KB: ZIP cannot pack them into it (1032:1 at most). The 4 KiB of zeros after the pixels
  // give the header's 256 chunk offsets room in the file, as in the 4 KB file that made
  // `nimbus compare` take 1.1 GB (before, OpenEXR read those offsets and read_exr allocated).
  const std::string big = with_data_window(dir / "small.exr", 4095, 4095) + std::string(4096, '\0');
  ASSERT_LT(big.size(), 8192u);
  nimbus::test::write_bytes(dir / "big.exr", big);
  const std::uint64_t peak_before = nimbus::peak_resident_bytes();
  expect_error<std::runtime_error>([&] { read_exr(dir / "big.exr"); },
                                   {(dir / "big.exr").string(), "4096x4096 pixels", "256.0 MiB as float RGBA",
                                    "KiB", "ZIP", "1032:1"});
  EXPECT_LT(nimbus::peak_resident_bytes(), peak_before + 64 * kMiB) << "the reader allocated for the declared window";

  // Each side must hold a pixel; the data window may hold at most 2^28 pixels (4 GiB as floats).
  nimbus::test::write_bytes(dir / "empty.exr", with_data_window(dir / "small.exr", -1, 7));
  expect_error<std::runtime_error>([&] { read_exr(dir / "empty.exr"); },
                                   {(dir / "empty.exr").string(), "holds no pixel"});
  nimbus::test::write_bytes(dir / "huge.exr", with_data_window(dir / "small.exr", 65535, 65535));
  expect_error<std::runtime_error>([&] { read_exr(dir / "huge.exr"); }, {"65536x65536", "larger than nimbus reads"});
  nimbus::test::write_bytes(dir / "edge.exr", with_data_window(dir / "small.exr", 2147483647, 0));
  expect_error<std::runtime_error>([&] { read_exr(dir / "edge.exr"); }, {"2147483648x1"});
}

TEST(ImageExrHostile, TheBoundFollowsTheDeclaredCompression) {
  TempDir dir;
  // 32 x 32 black pixels of half RGBA are 8 KiB of data, which this ZIP file holds in far less; called
  // uncompressed (NONE, 1:1), the same file cannot hold them.
  write_exr(dir / "zip.exr", Image(32, 32));
  std::string bytes = nimbus::test::read_bytes(dir / "zip.exr");
  ASSERT_LT(bytes.size(), 8192u);
  bytes[attribute_value(bytes, "compression", "compression")] = 0;  // NO_COMPRESSION (ImfCompression.h)
  nimbus::test::write_bytes(dir / "none.exr", bytes);
  expect_error<std::runtime_error>([&] { read_exr(dir / "none.exr"); }, {"32x32 pixels", "8.0 KiB", "NONE", "1:1"});
  bytes[attribute_value(bytes, "compression", "compression")] = 42;
  nimbus::test::write_bytes(dir / "unknown.exr", bytes);
  expect_error<std::runtime_error>([&] { read_exr(dir / "unknown.exr"); }, {"compression 42"});
}

TEST(ImageExrHostile, AnAttributeLongerThanTheFileIsRefusedBeforeAllocating) {
  TempDir dir;
  write_exr(dir / "small.exr", test_image(8, 8));
  std::string bytes = nimbus::test::read_bytes(dir / "small.exr");
  // The comments string says it holds 256 MiB: OpenEXR would size a string for it, then read.
  put_i32(bytes, attribute_value(bytes, "comments", "string") - 4, 256 << 20);
  nimbus::test::write_bytes(dir / "long.exr", bytes);
  const std::uint64_t peak_before = nimbus::peak_resident_bytes();
  expect_error<std::runtime_error>([&] { read_exr(dir / "long.exr"); },
                                   {"attribute 'comments' (string)", "256.0 MiB", "beyond the end of the file"});
  EXPECT_LT(nimbus::peak_resident_bytes(), peak_before + 64 * kMiB) << "the reader allocated for the attribute";
}

TEST(ImageExrHostile, LargeFlatImagesStillReadBackExactly) {
  // A flat image is the most compressible a render gets: ZIP packs its 16-line chunks near
  // deflate's 1032:1, and the bound must still let it through.
  TempDir dir;
  for (const float v : {0.0f, 0.25f}) {
    Image im(2048, 2048);
    for (std::size_t i = 0; i < im.rgba.size(); i += 4) {
      im.rgba[i] = v;
      im.rgba[i + 1] = 2 * v;
      im.rgba[i + 2] = 3 * v;
      im.rgba[i + 3] = 1.0f;
    }
    write_exr(dir / "flat.exr", im);
    const auto size = std::filesystem::file_size(dir / "flat.exr");
    const Image back = read_exr(dir / "flat.exr");
    ASSERT_EQ(back.width, 2048);
    ASSERT_EQ(back.height, 2048);
    EXPECT_TRUE(back.rgba == im.rgba) << "value " << v;  // 0, 0.25, 0.5, 0.75 and 1 are exact in half
    std::printf("  [measured] flat 2048x2048 half RGBA (value %g): %ju bytes, %.0f:1 of its 32 MiB\n", v,
                std::uintmax_t(size), 32.0 * kMiB / double(size));
  }
}

}  // namespace
