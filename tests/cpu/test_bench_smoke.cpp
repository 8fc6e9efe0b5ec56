// `nimbus bench noise`: the quick run finishes, prints a row for every noise kind and shows
// that the SIMD paths match the scalar path bit for bit; bad options are usage errors (exit 2).
#include <gtest/gtest.h>

#include "nimbus/render/image/image_io.hpp"
#include "nimbus/render/image/image_metrics.hpp"
#include "support/run_nimbus.hpp"
#include "support/vdb_fixtures.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace {

using Result = nimbus::test::RunResult;
Result run(const std::string& args) { return nimbus::test::run_nimbus(args); }

TEST(BenchNoise, QuickRunPrintsEveryKindAndBitIdenticalPaths) {
  const Result r = run("bench noise --quick");
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* row : {"nimbus value, 1 octave", "nimbus gradient, 1 octave", "nimbus wavelet, 1 octave",
                          "nimbus value, 6-octave fBm", "nimbus gradient, 6-octave fBm",
                          "nimbus wavelet, 6-octave fBm", "Wavelet tile build", "Multi-threaded"})
    EXPECT_NE(r.output.find(row), std::string::npos) << row << "\n" << r.output;
  EXPECT_NE(r.output.find("bit-identical"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("NOT bit-identical"), std::string::npos) << r.output;
}

TEST(BenchNoise, BadOptionsAreUsageErrors) {
  for (const char* args : {"bench noise --repeats 0", "bench noise --repeats -3", "bench noise --res 4",
                           "bench noise --res 513"}) {
    const Result r = run(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
  }
  const Result r = run("bench noise --repeats 0");
  EXPECT_NE(r.output.find("--repeats"), std::string::npos) << r.output;
}

// The FastNoise2 anchor is a library the user names: a path that is missing, not a shared
// library, or a library without FastNoise2's C API is a runtime error (exit 1) that names the
// path and what is wrong, before any timing; an empty path is a usage error.
TEST(BenchNoise, AFastNoise2PathThatIsNotTheLibraryIsNamed) {
  const nimbus::test::TempDir dir;
  const std::string missing = (dir / "no-such-libFastNoise.so").string();
  Result r = run("bench noise --quick --fastnoise2 " + missing);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("--fastnoise2 " + missing + ": cannot load it"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("nimbus gradient, 1 octave"), std::string::npos) << "timed before failing\n" << r.output;

  const std::string text = (dir / "not-a-library.so").string();
  nimbus::test::write_bytes(text, "not an ELF file\n");
  r = run("bench noise --quick --fastnoise2 " + text);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("--fastnoise2 " + text + ": cannot load it"), std::string::npos) << r.output;

  // A real shared library that is not FastNoise2: the C math library.
  r = run("bench noise --quick --fastnoise2 libm.so.6");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("--fastnoise2 libm.so.6: no symbol fnGetMetadataCount"), std::string::npos) << r.output;

  r = run("bench noise --quick --fastnoise2 ''");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--fastnoise2"), std::string::npos) << r.output;
}

}  // namespace

namespace {

// `nimbus bench look`: a tiny run prints every case and method with finite numbers, and the
// slicer's single scattering sits far below the multiply scattered reference (bias < -0.5),
// which the octaves reduce; bad options are usage errors.
TEST(BenchLook, TinyRunPrintsEveryCaseAndTheOctavesHelp) {
  const Result r = run("bench look --res 40x30 --ref-spp 32 --spp 4 --slices 24");
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* row : {"| front-lit | isotropic | slicer, single scattering", "| back-lit | hg:0.7 | path tracer, 4 spp",
                          "| back-lit | dual:0.7,-0.25,0.8 | slicer, 3 octaves (a 0.5, b 0.6)"})
    EXPECT_NE(r.output.find(row), std::string::npos) << row << "\n" << r.output;
  // The front-lit isotropic rows: single scattering's bias, then the 3-octave one's.
  // The column headed "bias" in the table's header row.
  auto column_of = [&](const std::string& name) {
    const std::size_t at = r.output.find("| lighting |");
    if (at == std::string::npos) return -1;
    const std::string header = r.output.substr(at, r.output.find('\n', at) - at);
    int bars = 0;
    for (std::size_t p = 0; p < header.size(); ++p) {
      if (header[p] == '|') ++bars;
      if (header.compare(p, name.size() + 2, " " + name + " ") == 0) return bars;
    }
    return -1;
  };
  const int bias_column = column_of("bias");
  ASSERT_GT(bias_column, 0) << r.output;
  auto bias_of = [&](const std::string& row) {
    const std::size_t at = r.output.find(row);
    if (at == std::string::npos) return 0.0;
    std::string line = r.output.substr(at, r.output.find('\n', at) - at);
    int bars = 0;
    std::size_t p = 0;
    // p starts on the row's first bar, so bias_column - 1 more bars reach the bias cell's.
    while (bars < bias_column - 1 && (p = line.find('|', p + 1)) != std::string::npos) ++bars;
    return std::stod(line.substr(p + 1));
  };
  const double single = bias_of("| front-lit | isotropic | slicer, single scattering");
  const double octaves = bias_of("| front-lit | isotropic | slicer, 3 octaves (a 0.5, b 0.6)");
  EXPECT_LT(single, -0.5) << r.output;
  EXPECT_GT(octaves, single + 0.2) << r.output;
  EXPECT_EQ(r.output.find("nan"), std::string::npos);
  EXPECT_EQ(run("bench look --spp 0").code, 2);
  EXPECT_EQ(run("bench look --preset nothing").code, 2);
  EXPECT_EQ(run("bench look --view above").code, 2);
  EXPECT_EQ(run("bench look --ms-lobes 3").code, 2);
  EXPECT_EQ(run("bench look --ms-diffusion-depth -1").code, 2);
  EXPECT_EQ(run("bench look --ms-similarity-depth 1001").code, 2);
  EXPECT_EQ(run("bench look --ms-progressive 0").code, 2);
  EXPECT_EQ(run("bench look --ms-progressive 1.5").code, 2);
  EXPECT_EQ(run("bench look --phases mie").code, 2);
  EXPECT_EQ(run("bench look --lighting side-lit").code, 2);
}

// `nimbus bench view --paths`: a name the table does not print is a usage error, named, before
// any context is made.
TEST(BenchSmoke, BenchViewRefusesAnUnknownPath) {
  const Result r = run("bench view --paths 'orbit|spiral'");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("'spiral'"), std::string::npos) << r.output;
}

// `nimbus bench look --view below --lighting back-lit --phases hg`: only the chosen case runs,
// with a row per light-volume variant asked for (lobes and fits on and off, a progressive build's
// first quarter), all finite.
TEST(BenchLook, ChosenCasesSeenFromBelow) {
  const Result r = run("bench look --preset stratus --view below --res 32x24 --ref-spp 8 --spp 2 --slices 24 --ms-photons 4096 "
                       "--ms-lobes 0,2 --ms-fits 0,1 --ms-progressive 0.25,1 --lighting back-lit --phases hg");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("seen from below"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("| back-lit | hg:0.7 | slicer, light volume 48 cells, 4096 photons, 2 lobe orders |"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("no lobes, no fits"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("4096 photons, 2 lobe orders, its first 0.25 traced |"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("| front-lit |"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("| back-lit | isotropic |"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("nan"), std::string::npos);
}

// `--images DIR` writes what the table measured: the error recomputed from the written files
// (half floats) is the printed one; the reference's standard error is finite and >= 0; a
// directory that cannot be made is a runtime error naming the option.
TEST(BenchLook, ImagesAreWhatTheTableMeasured) {
  const nimbus::test::TempDir dir;
  const std::string row = "| front-lit | isotropic | slicer, light volume 48 cells, 4096 photons, 2 lobe orders |";
  const Result r = run("bench look --res 32x24 --ref-spp 16 --spp 2 --slices 24 --ms-photons 4096 --lighting front-lit "
                       "--phases iso --images " + (dir / "out").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const std::size_t at = r.output.find(row);
  ASSERT_NE(at, std::string::npos) << r.output;
  // The row's cells after the method: ms | rel. RMSE | ...
  std::stringstream cells(r.output.substr(at + row.size()));
  std::string ms, rel;
  std::getline(cells, ms, '|');
  std::getline(cells, rel, '|');
  const double printed = std::stod(rel);
  const std::string stem = (dir / "out" / "front-lit_isotropic_").string();
  const nimbus::render::Image ref = nimbus::render::read_exr(stem + "reference.exr");
  const nimbus::render::Image lv = nimbus::render::read_exr(stem + "light-volume-48-cells-4096-photons-2-lobe-orders.exr");
  const nimbus::render::Image se = nimbus::render::read_exr(stem + "reference-std-error.exr");
  EXPECT_TRUE(std::filesystem::exists(stem + "single-scattering.exr"));
  ASSERT_EQ(ref.width, 32);
  ASSERT_EQ(ref.height, 24);
  const double recomputed = nimbus::render::compare_images(lv, ref).rel_rmse;
  EXPECT_GT(printed, 0.0);
  EXPECT_NEAR(recomputed, printed, 0.002 + 0.01 * printed) << r.output;
  for (std::size_t p = 0; p < se.rgba.size(); ++p) {
    EXPECT_TRUE(std::isfinite(se.rgba[p]) && se.rgba[p] >= 0.0f) << p;
    if (!(std::isfinite(se.rgba[p]) && se.rgba[p] >= 0.0f)) break;
  }
  nimbus::test::write_bytes(dir / "a-file", "x");
  const Result bad = run("bench look --res 8x6 --ref-spp 1 --spp 1 --images " + (dir / "a-file").string());
  EXPECT_EQ(bad.code, 1) << bad.output;
  EXPECT_NE(bad.output.find("--images"), std::string::npos) << bad.output;
}

}  // namespace
