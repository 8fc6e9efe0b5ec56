// `nimbus bench noise`: ns per sample of every noise kind, scalar path against the SIMD paths,
// beside Debian's libnoise (module::Perlin) and glm::perlin measured in the same run, and the
// error of each row against a named anchor (the scalar path for nimbus's SIMD paths, the
// documented range for the anchors). Protocol, that of the FastNoiseLite and FastNoise2 figures
// in docs/bench-noise.md: a 128^3 grid, x fastest, origin (0.137, 0.571, 0.913), one thread,
// thread CPU time, best of N, at spacings 1/16 and 1.37 lattice units. The output is a markdown
// document: paste it as is.
#include <time.h>
#include <unistd.h>

#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "bench_noise_fastnoise2.hpp"
#include "bench_noise_harness.hpp"
#include "cli/cli.hpp"
#include "nimbus/noise/noise.hpp"
#include "nimbus/noise/perlin_worley.hpp"

#if NIMBUS_HAVE_LIBNOISE
#include <libnoise/noise.h>
#endif
#if NIMBUS_HAVE_GLM
#include <glm/gtc/noise.hpp>
#include <glm/vec3.hpp>
#endif

namespace nimbus::cli {
namespace {

using namespace bench_noise;
using noise::Fractal;
using noise::Kind;
using noise::SimdLevel;

struct BenchOptions {
  int repeats = 5;
  int64_t res = 128;
  bool quick = false;
  bool all_levels = false;
  std::string fastnoise2 = NIMBUS_FASTNOISE2_LIBRARY;  // libFastNoise.so, or "" for none
  bool fastnoise2_only = false;
};

std::string spacing_name(double s) { return s == 1.0 / 16.0 ? "1/16" : fmt("%g", s); }

// ---------------------------------------------------------------------------------------------
// The measurements.

const std::array<double, 3> kOrigin{0.137, 0.571, 0.913};

noise::GridSpec cube(int64_t res, double spacing) {
  noise::GridSpec g;
  g.origin = kOrigin;
  g.spacing = spacing;
  g.res = {res, res, res};
  return g;
}

noise::NoiseParams params(Kind kind, int octaves) {
  noise::NoiseParams p;
  p.kind = kind;
  p.fractal = octaves == 1 ? Fractal::None : Fractal::Fbm;
  p.octaves = octaves;
  return p;  // frequency 1, lacunarity 2, gain 0.5, seed 0
}

// One thread, thread CPU time. A timed block covers at least 2^16 samples (the grid is
// evaluated `inner` times when it is smaller), so small grids are not dominated by clock noise.
double time_grid(const noise::NoiseField& field, const noise::GridSpec& grid, std::vector<float>& out,
                 SimdLevel level, int repeats) {
  noise::BatchOptions opt;
  opt.simd = level;
  opt.parallel = false;
  const int64_t inner = std::max<int64_t>(1, ((int64_t(1) << 16) + grid.count() - 1) / grid.count());
  const double secs = best_of(repeats, thread_cpu_seconds, [&] {
    for (int64_t i = 0; i < inner; ++i) noise::evaluate_grid(field, grid, out, opt);
  });
  return secs * 1e9 / double(grid.count() * inner);
}

Row measure_nimbus(const std::string& name, const noise::NoiseParams& p, const noise::GridSpec& grid,
                   const std::vector<SimdLevel>& levels, int repeats, std::string grid_note = {}) {
  const noise::NoiseField field(p);
  Row row;
  row.name = name;
  row.grid_note = std::move(grid_note);
  std::vector<float> ref(size_t(grid.count())), out(size_t(grid.count()));
  row.scalar_ns = time_grid(field, grid, ref, SimdLevel::Scalar, repeats);
  for (SimdLevel l : levels) {
    std::fill(out.begin(), out.end(), std::numeric_limits<float>::quiet_NaN());
    Cell c;
    c.ns = time_grid(field, grid, out, l, repeats);
    c.diff = diff_cell(ref, out);
    row.simd.push_back(c);
  }
  row.observed = range_cell(min_max(ref));
  const noise::Range r = field.range();
  row.documented = "[" + fmt("%g", r.lo) + ", " + fmt("%g", r.hi) + "]";
  return row;
}

// Perlin-Worley: both fBm grids through the batch path, then the remap, timed together.
Row measure_perlin_worley(const std::string& name, const noise::PerlinWorleyParams& p,
                          const noise::GridSpec& grid, const std::vector<SimdLevel>& levels, int repeats) {
  const noise::PerlinWorleyField field(p);
  std::vector<float> w(size_t(grid.count()));
  auto timed = [&](SimdLevel level, std::vector<float>& out) {
    noise::BatchOptions opt;
    opt.simd = level;
    opt.parallel = false;
    const int64_t inner = std::max<int64_t>(1, ((int64_t(1) << 16) + grid.count() - 1) / grid.count());
    const double secs = best_of(repeats, thread_cpu_seconds, [&] {
      for (int64_t i = 0; i < inner; ++i) {
        noise::evaluate_grid(field.perlin(), grid, out, opt);
        noise::evaluate_grid(field.worley(), grid, w, opt);
        for (size_t k = 0; k < out.size(); ++k) out[k] = field.combine(out[k], w[k]);
      }
    });
    return secs * 1e9 / double(grid.count() * inner);
  };
  Row row;
  row.name = name;
  std::vector<float> ref(size_t(grid.count())), out(size_t(grid.count()));
  row.scalar_ns = timed(SimdLevel::Scalar, ref);
  for (SimdLevel l : levels) {
    std::fill(out.begin(), out.end(), std::numeric_limits<float>::quiet_NaN());
    Cell c;
    c.ns = timed(l, out);
    c.diff = diff_cell(ref, out);
    row.simd.push_back(c);
  }
  row.observed = range_cell(min_max(ref));
  row.documented = "[0, 1]";
  return row;
}

// An anchor evaluated point by point in the same order (x fastest) at the same coordinates.
Row measure_anchor(const std::string& name, const std::string& documented, const noise::GridSpec& grid,
                   int repeats, const std::function<float(double, double, double)>& f) {
  std::vector<float> out(size_t(grid.count()));
  const double secs = best_of(repeats, thread_cpu_seconds, [&] {
    size_t n = 0;
    for (int64_t k = 0; k < grid.res[2]; ++k)
      for (int64_t j = 0; j < grid.res[1]; ++j)
        for (int64_t i = 0; i < grid.res[0]; ++i) {
          const auto p = grid.point(i, j, k);
          out[n++] = f(p[0], p[1], p[2]);
        }
  });
  Row row;
  row.name = name;
  row.scalar_ns = secs * 1e9 / double(grid.count());
  row.observed = range_cell(min_max(out));
  row.documented = documented;
  return row;
}

// The SIMD levels timed beside the scalar path: the best, or every supported one up to it.
std::vector<SimdLevel> simd_levels(bool all_levels) {
  const SimdLevel best = noise::best_simd_level();
  std::vector<SimdLevel> levels;
  if (all_levels) {
    for (SimdLevel l : {SimdLevel::Sse41, SimdLevel::Avx2, SimdLevel::Avx512})
      if (noise::simd_level_supported(l) && int(l) <= int(best)) levels.push_back(l);
  } else if (best != SimdLevel::Scalar) {
    levels.push_back(best);
  }
  return levels;
}

void print_preamble(const BenchOptions& o, const std::string& load_before) {
  const int64_t res = o.res;
  std::printf("## nimbus bench noise\n\n");
  std::printf("- CPU: %s, %ld logical CPUs online; TBB default concurrency %d\n", cpu_model().c_str(),
              sysconf(_SC_NPROCESSORS_ONLN), tbb::info::default_concurrency());
  std::printf("- Compiler: g++ %s; harness TU: %s\n", __VERSION__, harness_flags().c_str());
  std::printf("- Date: %s; load average (1/5/15 min) at start: %s\n", utc_now().c_str(), load_before.c_str());
  std::printf("- Best SIMD level: **%s**%s\n", std::string(noise::to_string(noise::best_simd_level())).c_str(),
              std::getenv("NIMBUS_SIMD") ? " (lowered by NIMBUS_SIMD)" : "");
  std::printf("- Protocol: %lld^3 grid (%lld samples), x fastest, origin (0.137, 0.571, 0.913), frequency 1, "
              "seed 0; one thread (BatchOptions.parallel = false); thread CPU time "
              "(CLOCK_THREAD_CPUTIME_ID); best of %d repeat%s. fBm: 6 octaves, lacunarity 2, gain 0.5.\n",
              static_cast<long long>(res), static_cast<long long>(res * res * res), o.repeats, o.repeats == 1 ? "" : "s");
  std::printf("- Error column: nimbus SIMD paths against nimbus's scalar path (the contract is bit-identical). "
              "Anchors are different functions, so their error is shown as observed range against documented "
              "range.\n\n");
}

// nimbus's rows at one spacing: every kind at 1 and 6 octaves, Perlin-Worley, projected wavelet.
void add_nimbus_rows(std::vector<Row>& rows, const noise::GridSpec& grid, const std::vector<SimdLevel>& levels,
                     int repeats, int64_t res) {
  for (Kind kind : {Kind::Value, Kind::Gradient, Kind::Wavelet, Kind::Worley}) {
    const std::string k(noise::to_string(kind));
    rows.push_back(measure_nimbus("nimbus " + k + ", 1 octave", params(kind, 1), grid, levels, repeats));
    rows.push_back(measure_nimbus("nimbus " + k + ", 6-octave fBm", params(kind, 6), grid, levels, repeats));
  }
  rows.push_back(measure_perlin_worley("nimbus perlin-worley, 4-octave gradient fBm remapped by 3-octave Worley fBm",
                                       noise::PerlinWorleyParams{}, grid, levels, repeats));
  {
    noise::NoiseParams p = params(Kind::Wavelet, 1);
    p.projected = true;  // normal (0, 0, 1)
    noise::GridSpec slice = grid;  // fewer samples: projection costs far more per sample
    slice.res = {res / 2, res / 2, 1};
    rows.push_back(measure_nimbus("nimbus wavelet projected, 1 octave", p, slice, levels, repeats,
                                  std::to_string(res / 2) + "²×1 grid"));
  }
}

// The anchors at one spacing, point by point: libnoise's module::Perlin and glm::perlin.
void add_anchor_rows([[maybe_unused]] std::vector<Row>& rows, [[maybe_unused]] const noise::GridSpec& grid,
                     [[maybe_unused]] int repeats) {
#if NIMBUS_HAVE_LIBNOISE
  {
    const std::string doc = "[-1, 1] \"usually\", no guarantee (perlin.h)";
    ::noise::module::Perlin one;
    one.SetOctaveCount(1);
    one.SetNoiseQuality(::noise::QUALITY_BEST);
    rows.push_back(measure_anchor("libnoise module::Perlin, 1 octave, QUALITY_BEST", doc, grid, repeats,
                                  [&](double x, double y, double z) { return float(one.GetValue(x, y, z)); }));
    ::noise::module::Perlin six;  // defaults: 6 octaves, persistence 0.5, lacunarity 2, QUALITY_STD
    rows.push_back(measure_anchor("libnoise module::Perlin, 6 octaves (defaults, QUALITY_STD)", doc, grid,
                                  repeats,
                                  [&](double x, double y, double z) { return float(six.GetValue(x, y, z)); }));
  }
#endif
#if NIMBUS_HAVE_GLM
  {
    const std::string doc = "none documented";
    rows.push_back(measure_anchor("glm::perlin(vec3), 1 octave", doc, grid, repeats,
                                  [](double x, double y, double z) {
                                    return glm::perlin(glm::vec3(float(x), float(y), float(z)));
                                  }));
    rows.push_back(measure_anchor("glm::perlin fBm loop, 6 octaves, ÷ Σamp", doc, grid, repeats,
                                  [](double x, double y, double z) {
                                    const glm::vec3 p{float(x), float(y), float(z)};
                                    float sum = 0.0f, amp = 1.0f, freq = 1.0f;
                                    for (int i = 0; i < 6; ++i) {
                                      sum += amp * glm::perlin(p * freq);
                                      freq *= 2.0f;
                                      amp *= 0.5f;
                                    }
                                    return sum * (1.0f / 1.96875f);
                                  }));
  }
#endif
}

// Wavelet tile build: wall clock, a fresh tile per seed (not the shared cache). The build
// runs on TBB, so it is timed both in the default arena and in an arena of one thread.
void wavelet_build_rows(const BenchOptions& o) {
  const int builds = o.quick ? 1 : std::max(o.repeats, 3);
  std::printf("### Wavelet tile build (wall clock, a fresh tile per seed)\n\n"
              "| Tile | threads | builds (seeds) | best ms | worst ms |\n|---|---:|---:|---:|---:|\n");
  for (int threads : {tbb::info::default_concurrency(), 1}) {
    tbb::task_arena arena(threads);
    double best_s = std::numeric_limits<double>::infinity(), worst_s = 0.0;
    for (int s = 0; s < builds; ++s) {
      arena.execute([&] {
        const double t0 = wall_seconds();
        const noise::WaveletTile tile{128, uint32_t(1000 + s)};
        const double t = wall_seconds() - t0;
        best_s = std::min(best_s, t);
        worst_s = std::max(worst_s, t);
      });
    }
    std::printf("| WaveletTile(128, seed): 128³ coefficients, 8 MiB | %d | %d | %.1f | %.1f |\n", threads,
                builds, best_s * 1e3, worst_s * 1e3);
    if (threads == 1) break;
  }
  std::printf("\n");
}

// Multi-threaded throughput: wall clock, TBB's default arena, against one thread at the best
// SIMD level on the same grid.
void threaded_rows(const BenchOptions& o, int64_t mt_res) {
  const SimdLevel best = noise::best_simd_level();
  const noise::GridSpec grid = cube(mt_res, 1.0 / 16.0);
  const int64_t n = grid.count();
  std::printf("### Multi-threaded throughput (%lld³ grid, spacing 1/16, %s, wall clock, best of %d)\n\n",
              static_cast<long long>(mt_res), std::string(noise::to_string(best)).c_str(), o.repeats);
  std::printf("| Noise | threads | 1 thread ns/sample | 1 thread Msamples/s | parallel ns/sample | "
              "parallel Msamples/s | speedup | parallel output vs 1 thread |\n|---|---:|---:|---:|---:|---:|---:|---|\n");
  std::vector<float> one(static_cast<size_t>(n)), par(static_cast<size_t>(n));
  for (Kind kind : {Kind::Gradient, Kind::Wavelet}) {
    const noise::NoiseField field(params(kind, 6));
    noise::BatchOptions single{best, false}, multi{best, true};
    const double t1 = best_of(o.repeats, wall_seconds, [&] { noise::evaluate_grid(field, grid, one, single); });
    const double tp = best_of(o.repeats, wall_seconds, [&] { noise::evaluate_grid(field, grid, par, multi); });
    const double ns1 = t1 * 1e9 / double(n), nsp = tp * 1e9 / double(n);
    std::printf("| nimbus %s, 6-octave fBm | %d | %s | %s | %s | %s | %.2f× | %s |\n",
                std::string(noise::to_string(kind)).c_str(), tbb::info::default_concurrency(),
                ns_cell(ns1).c_str(), ms_cell(ns1).c_str(), ns_cell(nsp).c_str(), ms_cell(nsp).c_str(),
                t1 / tp, diff_cell(one, par).c_str());
  }
  std::printf("\n");
}

int run_bench_noise(BenchOptions o) {
  if (o.repeats < 1) throw UsageError("--repeats: " + std::to_string(o.repeats) + " must be >= 1");
  if (o.res < 8 || o.res > 512) throw UsageError("--res: " + std::to_string(o.res) + " must be in [8, 512]");
  if (o.quick) {  // overrides --repeats and --res
    o.repeats = 1;
    o.res = 64;
  }
  if (o.fastnoise2_only && o.fastnoise2.empty())
    throw UsageError("--fastnoise2-only: needs --fastnoise2 PATH (or NIMBUS_FASTNOISE2_LIBRARY at configure time)");
  // Loaded first, so that a bad path fails before minutes of timing.
  std::unique_ptr<FastNoise2> fn2;
  if (!o.fastnoise2.empty()) fn2 = std::make_unique<FastNoise2>(o.fastnoise2);
  const std::vector<SimdLevel> levels = simd_levels(o.all_levels);
  const int64_t res = o.res;
  const int64_t mt_res = std::max<int64_t>(res, std::min<int64_t>(2 * res, 256));
  ensure_fits_in_memory(uint64_t(mt_res * mt_res * mt_res), 2 * sizeof(float),
                        "a " + std::to_string(mt_res) + "^3 benchmark grid");
  const std::string load_before = load_average();

  // Keep the 128^3 wavelet tile (seed 0) alive, so every wavelet field below shares it and no
  // timed block or field construction in the loop rebuilds it.
  const noise::NoiseField wavelet_keepalive(params(Kind::Wavelet, 1));
  print_preamble(o, load_before);
  if (fn2) fastnoise2_rows(*fn2, res, o.repeats);
  if (o.fastnoise2_only) {
    std::printf("Load average at end: %s\n", load_average().c_str());
    return 0;
  }
  for (double spacing : {1.0 / 16.0, 1.37}) {
    const noise::GridSpec grid = cube(res, spacing);
    std::vector<Row> rows;
    add_nimbus_rows(rows, grid, levels, o.repeats, res);
    add_anchor_rows(rows, grid, o.repeats);
    std::printf("### Spacing %s lattice units (%s samples per cell), one thread\n\n", spacing_name(spacing).c_str(),
                fmt("%.3g", 1.0 / spacing).c_str());
    print_rows(rows, levels);
    std::printf("\n");
  }
#if !NIMBUS_HAVE_LIBNOISE
  std::printf("(libnoise anchor not built: libnoise headers or library not found)\n\n");
#endif
#if !NIMBUS_HAVE_GLM
  std::printf("(glm anchor not built: glm headers not found)\n\n");
#endif
  if (!fn2)
    std::printf("(FastNoise2 anchor not given: --fastnoise2 PATH, or -DNIMBUS_FASTNOISE2_LIBRARY=PATH at configure "
                "time; docs/bench-noise.md says how to build it)\n\n");
  wavelet_build_rows(o);
  threaded_rows(o, mt_res);
  std::printf("Load average at end: %s\n", load_average().c_str());
  return 0;
}

}  // namespace

void add_bench_noise(CLI::App& bench, Action& action) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd =
      bench.add_subcommand("noise", "ns per sample of every noise kind against libnoise and glm (markdown table)");
  cmd->add_option("--repeats", o->repeats, "timed repeats per row; the best is kept (>= 1)")->capture_default_str();
  cmd->add_option("--res", o->res, "samples per axis of the cube (8..512)")->capture_default_str();
  cmd->add_flag("--quick", o->quick, "smoke test: overrides to --repeats 1 --res 64");
  cmd->add_flag("--all-levels", o->all_levels, "time every supported SIMD level, not only the best");
  cmd->add_option("--fastnoise2", o->fastnoise2,
                  "a FastNoise2 shared library (libFastNoise.so, built from its public source) to time beside nimbus")
      ->capture_default_str();
  cmd->add_flag("--fastnoise2-only", o->fastnoise2_only, "time only the FastNoise2 comparison");
  cmd->callback([&action, o] { action = [o] { return run_bench_noise(*o); }; });
}

}  // namespace nimbus::cli
