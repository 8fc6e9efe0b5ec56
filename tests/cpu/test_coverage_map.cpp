// Coverage (weather) maps (coverage_map.hpp): PNGs read as untrusted files, sampled bilinearly,
// and what they do to a field: no cloud voxel where the map is 0, the layout as without a map
// where it is 1 everywhere.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <png.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "nimbus/base/memory.hpp"
#include "nimbus/volume/coverage_map.hpp"
#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/preset.hpp"

namespace nimbus::volume {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const fs::path d = fs::temp_directory_path() / ("nimbus_coverage_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

// A PNG written by libpng's own writer, from 8-bit or 16-bit samples.
void write_png(const fs::path& path, int w, int h, int channels, const std::vector<uint16_t>& samples, bool sixteen) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  image.width = uint32_t(w);
  image.height = uint32_t(h);
  image.format = (channels == 1 ? PNG_FORMAT_GRAY : PNG_FORMAT_RGB) | (sixteen ? PNG_FORMAT_FLAG_LINEAR : 0);
  bool ok;
  if (sixteen) {
    ok = png_image_write_to_file(&image, path.c_str(), 0, samples.data(), 0, nullptr);
  } else {
    std::vector<uint8_t> bytes(samples.begin(), samples.end());
    ok = png_image_write_to_file(&image, path.c_str(), 0, bytes.data(), 0, nullptr);
  }
  ASSERT_TRUE(ok) << image.message;
}

TEST(CoverageMap, PngsReadTheirRedChannelAndSampleBilinearly) {
  const fs::path dir = temp_dir();
  // 8-bit grey, 3 x 2: row 0 is the north edge.
  write_png(dir / "grey.png", 3, 2, 1, {0, 51, 255, 102, 204, 0}, false);
  const auto g = read_coverage_png((dir / "grey.png").string());
  ASSERT_EQ(g->width, 3);
  ASSERT_EQ(g->height, 2);
  EXPECT_FLOAT_EQ(g->value[1], 51.0f / 255.0f);
  EXPECT_FLOAT_EQ(g->value[3], 102.0f / 255.0f);
  // 16-bit RGB: red is read, green and blue are not.
  write_png(dir / "rgb16.png", 2, 1, 3, {65535, 0, 0, 13107, 65535, 65535}, true);
  const auto c = read_coverage_png((dir / "rgb16.png").string());
  EXPECT_FLOAT_EQ(c->value[0], 1.0f);
  EXPECT_FLOAT_EQ(c->value[1], 0.2f);
  // Over [0, 300] x [0, 200]: pixel centres at x = 50, 150, 250 and y = 150 (row 0), 50 (row 1).
  const CoverageMap m(g, {0.0, 0.0}, {300.0, 200.0}, false, false);
  EXPECT_NEAR(m.at({150.0, 150.0}), 51.0 / 255.0, 1e-7);
  EXPECT_NEAR(m.at({100.0, 150.0}), 0.5 * (0.0 + 51.0) / 255.0, 1e-7);
  EXPECT_NEAR(m.at({150.0, 100.0}), 0.5 * (51.0 + 204.0) / 255.0, 1e-7);
  EXPECT_NEAR(m.at({-1000.0, 150.0}), 0.0, 1e-7);                // beyond the west edge: the edge pixel
  const CoverageMap wrap(g, {0.0, 0.0}, {300.0, 200.0}, true, false);  // periodic: east edge meets the west
  EXPECT_NEAR(wrap.at({300.0, 150.0}), 0.5 * (255.0 + 0.0) / 255.0, 1e-7);
  EXPECT_NEAR(wrap.at({300.0 + 150.0, 150.0 - 200.0}), wrap.at({150.0, 150.0}), 1e-12);
  fs::remove_all(dir);
}

TEST(CoverageMap, UntrustedFilesAreRefusedNamingThem) {
  const fs::path dir = temp_dir();
  auto refused = [](const std::string& path, const char* word) {
    try {
      read_coverage_png(path);
      ADD_FAILURE() << path << " accepted";
    } catch (const std::runtime_error& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(path), std::string::npos) << m;
      EXPECT_NE(m.find(word), std::string::npos) << m;
    }
  };
  refused((dir / "missing.png").string(), "missing.png");
  refused(dir.string(), "");  // a directory
  {
    std::ofstream f(dir / "text.png");
    f << "not a png at all";
  }
  refused((dir / "text.png").string(), "PNG");
  // Too wide: refused from the header, before the pixels are allocated.
  write_png(dir / "wide.png", kMaxCoverageMapSide + 1, 1, 1, std::vector<uint16_t>(kMaxCoverageMapSide + 1, 7), false);
  refused((dir / "wide.png").string(), "pixels");
  // Truncated: the header is sound, the pixels are missing.
  write_png(dir / "whole.png", 64, 64, 1, std::vector<uint16_t>(64 * 64, 200), false);
  {
    std::ifstream in(dir / "whole.png", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    std::ofstream out(dir / "cut.png", std::ios::binary);
    out << bytes.substr(0, 60);
  }
  refused((dir / "cut.png").string(), "PNG");
  EXPECT_THROW(coverage_from_values({0.5f, 1.5f}, 2, 1, "array"), std::invalid_argument);
  EXPECT_THROW(coverage_from_values({0.5f, NAN}, 2, 1, "array"), std::invalid_argument);
  EXPECT_THROW(coverage_from_values({0.5f}, 2, 1, "array"), std::invalid_argument);
  fs::remove_all(dir);
}

// Hostile files: what is not a regular file is refused without being read, and a
// header cannot make the reader allocate more than the file can hold.
TEST(CoverageMap, AFifoIsRefusedWithoutReadingFromIt) {
  const fs::path dir = temp_dir();
  const fs::path fifo = dir / "f.png";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // Held open for writing with bytes in it: a reader that opened it would take them, not block.
  const int fd = ::open(fifo.c_str(), O_RDWR | O_NONBLOCK);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::write(fd, "not a PNG", 9), 9);
  try {
    read_coverage_png(fifo.string());
    ADD_FAILURE() << "a FIFO was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(fifo.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("is a FIFO"), std::string::npos) << e.what();
  }
  char buf[16];
  EXPECT_EQ(::read(fd, buf, sizeof buf), 9) << "the reader took bytes from the FIFO";
  ::close(fd);
  fs::remove_all(dir);
}

TEST(CoverageMap, AHeaderDeclaringMorePixelsThanTheFileHoldsIsRefusedBeforeAllocating) {
  const fs::path dir = temp_dir();
  write_png(dir / "small.png", 64, 64, 1, std::vector<uint16_t>(64 * 64, 200), false);
  std::string bytes;
  {
    std::ifstream in(dir / "small.png", std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  ASSERT_LT(bytes.size(), 1024u);
  // IHDR (PNG specification 11.2.2): width and height, big-endian, at bytes 16 and 20, then the
  // chunk's CRC-32 over its type and 13 data bytes, at byte 29. 8192 x 8192 8-bit pixels are
  // 64 MiB of image data, which deflate (1032:1 at most) cannot pack into under 1 KB; the reader
  // would have allocated 448 MB for them (floats and decoded RGB).
  for (int at : {16, 20}) {
    const uint32_t v = 8192;
    for (int i = 0; i < 4; ++i) bytes[at + i] = char((v >> (24 - 8 * i)) & 0xff);
  }
  const uint32_t crc = uint32_t(crc32(0, reinterpret_cast<const Bytef*>(bytes.data() + 12), 17));
  for (int i = 0; i < 4; ++i) bytes[29 + i] = char((crc >> (24 - 8 * i)) & 0xff);
  {
    std::ofstream out(dir / "big.png", std::ios::binary);
    out << bytes;
  }
  const uint64_t peak_before = peak_resident_bytes();
  try {
    read_coverage_png((dir / "big.png").string());
    ADD_FAILURE() << "accepted";
  } catch (const std::runtime_error& e) {
    const std::string m = e.what();
    for (const char* word : {"big.png", "8192 x 8192 pixels of 8 bits", "64 MiB", "deflate", "1032:1"})
      EXPECT_NE(m.find(word), std::string::npos) << word << " not in: " << m;
  }
  EXPECT_LT(peak_resident_bytes(), peak_before + (uint64_t(64) << 20)) << "the reader allocated for the declared size";
  fs::remove_all(dir);
}

TEST(CoverageMap, ALargeFlatMapStillReads) {
  // A flat map is the most compressible there is, near deflate's 1032:1: the bound lets it through.
  const fs::path dir = temp_dir();
  write_png(dir / "flat.png", 4096, 4096, 1, std::vector<uint16_t>(size_t(4096) * 4096, 200), false);
  const auto size = fs::file_size(dir / "flat.png");
  const auto m = read_coverage_png((dir / "flat.png").string());
  ASSERT_EQ(m->width, 4096);
  ASSERT_EQ(m->height, 4096);
  for (const float v : m->value) ASSERT_EQ(v, 200.0f / 255.0f);
  std::printf("  [measured] flat 4096 x 4096 8-bit grey PNG: %ju bytes, %.0f:1\n", std::uintmax_t(size),
              4096.0 * 4097.0 / double(size));
  fs::remove_all(dir);
}

CloudParams small_field(bool periodic) {
  CloudParams p = cloud_from_json(load_preset("cumulus-field").at("cloud"), "cumulus-field");
  p.field->size_m = {4000.0, 4000.0};
  p.field->max_diameter_m = 1200.0;
  p.field->periodic = periodic;
  return p;
}

TEST(CoverageMap, ABlackHalfHoldsNoCloudVoxel) {
  const fs::path dir = temp_dir();
  // 64 x 16 pixels: the west half white, the east half black.
  std::vector<uint16_t> px(64 * 16);
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 64; ++i) px[size_t(j) * 64 + i] = i < 32 ? 255 : 0;
  write_png(dir / "half.png", 64, 16, 1, px, false);
  for (const bool periodic : {false, true}) {
    CloudParams p = small_field(periodic);
    p.coverage_map = (dir / "half.png").string();
    p.coverage_image = read_coverage_png(p.coverage_map);
    GenerateOptions o;
    o.voxel_size = 20.0;
    const auto grid = generate_density(p, o);
    // The map is 0 from the centre of pixel 32 on (x = -2000 + 32.5 * 62.5 = 31.25 m); periodic,
    // it rises again past the centre of pixel 63 (1968.75 m), towards the white west edge.
    const double black_from = 31.25, black_to = periodic ? 1968.75 : 1e30;
    int64_t west = 0, east = 0;
    for (auto it = grid->cbeginValueOn(); it; ++it) {
      const double x = it.getCoord().x() * o.voxel_size;
      if (x > black_from && x < black_to) {
        ++east;
        ADD_FAILURE() << "cloud voxel at x = " << x << " where the map is black";
        break;
      }
      ++west;
    }
    EXPECT_EQ(east, 0);
    EXPECT_GT(west, 10000) << "the white half should hold cloud";
    // No cloud is placed where the map is black.
    const CoverageMap map(p.coverage_image, {-2000.0, -2000.0}, {4000.0, 4000.0}, periodic, false);
    for (const FieldCloud& c : field_layout(*p.field, &map)) EXPECT_GT(map.at(c.center_m), 0.0);
    std::printf("  [measured] half-black map (%s): %lld cloud voxels in the white half, none in the black\n",
                periodic ? "periodic" : "not periodic", static_cast<long long>(west));
  }
  fs::remove_all(dir);
}

TEST(CoverageMap, AWhiteMapGivesTheVoxelsOfNoMap) {
  for (const bool periodic : {false, true}) {
    const CloudParams plain = small_field(periodic);
    CloudParams white = plain;
    white.coverage_image = coverage_from_values(std::vector<float>(16 * 16, 1.0f), 16, 16, "white");
    GenerateOptions o;
    o.voxel_size = 25.0;
    o.time = 12.0;
    const auto a = generate_density(plain, o), b = generate_density(white, o);
    ASSERT_EQ(a->activeVoxelCount(), b->activeVoxelCount());
    auto acc = b->getConstAccessor();
    for (auto it = a->cbeginValueOn(); it; ++it) ASSERT_EQ(*it, acc.getValue(it.getCoord())) << it.getCoord();
  }
}

TEST(CoverageMap, AGreyMapThinsTheFieldAndCanFlattenIt) {
  CloudParams p = small_field(true);
  const auto plain = field_layout(*p.field);
  const auto grey = coverage_from_values(std::vector<float>(4, 0.5f), 2, 2, "grey");
  const CoverageMap cover(grey, {-2000.0, -2000.0}, {4000.0, 4000.0}, true, false);
  const CoverageMap tall(grey, {-2000.0, -2000.0}, {4000.0, 4000.0}, true, true);
  double area_plain = 0, area_grey = 0, depth_cover = 0, depth_tall = 0;
  for (const FieldCloud& c : plain) area_plain += c.diameter_m * c.diameter_m;
  const auto a = field_layout(*p.field, &cover), b = field_layout(*p.field, &tall);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    area_grey += a[i].diameter_m * a[i].diameter_m;
    depth_cover += a[i].depth_m;
    depth_tall += b[i].depth_m;
  }
  // Half the area to cover; the same clouds, half as deep, when the map sets heights too.
  EXPECT_NEAR(area_grey / area_plain, 0.5, 0.1);
  EXPECT_NEAR(depth_tall / depth_cover, 0.5, 1e-9);
}

}  // namespace
}  // namespace nimbus::volume
