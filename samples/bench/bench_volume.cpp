// `nimbus bench volume`: generation speed per preset beside its error, against the same field
// evaluated naively at every voxel (the anchor), with the octave limit on and off; plus file
// size, write time and read time (sealed and foreign, bench_volume_read.hpp).
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <thread>

#include "bench_volume_keyframes.hpp"
#include "bench_volume_read.hpp"
#include "cli/cli.hpp"
#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/preset.hpp"
#include "nimbus/volume/vdb_io.hpp"

namespace nimbus::cli {
namespace {

struct BenchVolumeArgs {
  std::string presets;         // comma-separated; empty: all
  std::string res = "128,256";
  int naive_max = 128;         // naive anchors only up to this resolution (they are slow)
  std::string naive_always = "cumulus-mediocris";  // ... except for this preset
  bool quick = false;
  bool field = true;           // the cumulus field section
  int keyframes = 6;           // the sky keyframe section's keyframes (0: none)
  bool keyframes_only = false;
};

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

struct Diff {
  double max = 0.0, rms = 0.0;
};

// Over the union of both grids' active voxels (inactive = 0).
Diff difference(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b) {
  Diff d;
  double sum2 = 0.0;
  int64_t n = 0;
  auto visit = [&](const openvdb::FloatGrid& x, const openvdb::FloatGrid& y, bool count_shared) {
    auto acc = y.getConstAccessor();
    for (auto it = x.cbeginValueOn(); it; ++it) {
      float v = 0.0f;
      const bool shared = acc.probeValue(it.getCoord(), v);
      if (shared && !count_shared) continue;
      const double e = std::fabs(double(*it) - (shared ? double(v) : 0.0));
      d.max = std::max(d.max, e);
      sum2 += e * e;
      ++n;
    }
  };
  visit(a, b, true);
  visit(b, a, false);
  d.rms = n ? std::sqrt(sum2 / double(n)) : 0.0;
  return d;
}

std::string diff_text(const Diff& d) {
  if (d.max == 0.0) return "0 (identical)";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g / %.3g", d.max, d.rms);
  return buf;
}

double peak_rss_gb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / (1024.0 * 1024.0);  // kilobytes on Linux
}

// The cumulus field: 10 x 10 km (2 x 2 km with --quick) at 20 m voxels, 3 km of
// height, with time, active voxels, memory and file size; the anchor is the naive every-voxel
// path on a 1 x 1 km column of the field, against the sparse path on the same column.
void bench_field(bool quick, const std::filesystem::path& tmp) {
  nlohmann::json doc = volume::load_preset("cumulus-field");
  volume::CloudParams params = volume::cloud_from_json(doc.at("cloud"), "cumulus-field");
  const double side = quick ? 2000.0 : 10000.0;
  params.field->size_m = {side, side};
  volume::GenerateOptions o;
  o.voxel_size = 20.0;
  volume::GenerateStats s;
  const double rss0 = peak_rss_gb();
  const auto grid = volume::generate_density(params, o, &s);
  const double rss1 = peak_rss_gb();
  const int64_t clouds = static_cast<int64_t>(volume::field_layout(*params.field).size());
  volume::ExportInfo info;
  info.preset = "cumulus-field";
  volume::ExportOptions eo;
  eo.half_float = true;
  const auto path = tmp / "cumulus-field.half.vdb";
  const auto t0 = std::chrono::steady_clock::now();
  volume::write_volume_vdb(path, {grid}, info, eo);
  const double write_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const volume::Aabb b = volume::CloudModel(params, o.voxel_size, 0.0).bounds();
  std::printf("\n### Cloud field (cumulus-field, %g x %g km at 20 m)\n\n", side / 1000, side / 1000);
  std::printf("| field | clouds | bounds (m) | bounds voxels | s (%u threads) | active voxels | grid memory MB | peak RSS GB (before -> after) | file MB (half) | write s |\n",
              std::thread::hardware_concurrency());
  std::printf("|---|---:|---|---:|---:|---:|---:|---|---:|---:|\n");
  std::printf("| %g x %g km | %lld | %.0f x %.0f x %.0f | %lld | %.2f | %lld | %.1f | %.2f -> %.2f | %.1f | %.2f |\n", side / 1000,
              side / 1000, static_cast<long long>(clouds), b.hi.x - b.lo.x, b.hi.y - b.lo.y, b.hi.z - b.lo.z,
              static_cast<long long>(s.voxels_in_bounds), s.seconds, static_cast<long long>(s.active_voxels),
              double(grid->memUsage()) / 1e6, rss0, rss1, double(std::filesystem::file_size(path)) / 1e6, write_s);
  // Anchor: a 1 x 1 km column (50 x 50 voxels, every height) at the field's centre.
  volume::GenerateOptions c = o;
  c.clip = openvdb::CoordBBox({-25, -25, -1000000}, {24, 24, 1000000});
  volume::GenerateStats sn, ss;
  c.sparse = false;
  const auto naive = volume::generate_density(params, c, &sn);
  c.sparse = true;
  const auto sparse = volume::generate_density(params, c, &ss);
  std::printf("\n| 1 x 1 km column | bounds voxels | s | Mvoxels/s | error vs anchor (max / RMS) |\n|---|---:|---:|---:|---|\n");
  std::printf("| naive (anchor) | %lld | %.3f | %.2f | anchor |\n", static_cast<long long>(sn.voxels_in_bounds), sn.seconds,
              double(sn.voxels_in_bounds) / sn.seconds * 1e-6);
  std::printf("| **sparse** (default) | %lld | %.3f | %.2f | %s |\n", static_cast<long long>(ss.voxels_in_bounds),
              ss.seconds, double(ss.voxels_in_bounds) / ss.seconds * 1e-6, diff_text(difference(*sparse, *naive)).c_str());
}

int run_bench_volume(const BenchVolumeArgs& a) {
  if (a.keyframes_only) {
    std::printf("## nimbus bench volume\n");
    bench_sky_keyframes(std::max(a.keyframes, 1));
    return 0;
  }
  std::vector<std::string> names = split(a.presets);
  if (names.empty())
    for (const auto& p : volume::list_presets()) names.push_back(p.name);
  std::vector<int> resolutions;
  for (const std::string& r : split(a.quick ? "48" : a.res)) {
    const int v = std::atoi(r.c_str());
    if (v < 8 || v > 1024) throw UsageError("--res: each resolution must be in [8, 1024] (got '" + r + "')");
    resolutions.push_back(v);
  }
  if (a.quick) names.resize(std::min<size_t>(names.size(), 2));
  std::printf("## nimbus bench volume\n\n");
  char host[256] = "";
  std::printf("- %u hardware threads; resolution N = voxels across the cloud's largest extent at t = 0\n",
              std::thread::hardware_concurrency());
  (void)host;
  std::printf("- modes: naive = every voxel of the bounding box through the scalar path (the anchor); "
              "sparse = leaf blocks near a shape, noise only where coverage can give density, SIMD batches\n");
  std::printf("- error = max / RMS |density difference| over the union of active voxels: sparse against the "
              "naive anchor of the same octaves, and octave-limited against all octaves\n\n");
  std::printf("| preset | N | voxel m | bounds voxels | mode | octaves | s | Mvoxels/s (bounds) | noise evals | active | error vs anchor | error of the octave limit |\n");
  std::printf("|---|---:|---:|---:|---|---:|---:|---:|---:|---:|---|---|\n");
  const auto tmp = std::filesystem::temp_directory_path() / ("nimbus_bench_volume_" + std::to_string(::getpid()));
  std::filesystem::create_directories(tmp);
  struct FileRow {
    std::string preset;
    int res;
    int64_t active;
    uintmax_t half_bytes, float_bytes;
    double half_s, float_s;
  };
  std::vector<FileRow> files;
  for (const std::string& name : names) {
    nlohmann::json doc;
    try {
      doc = volume::load_preset(name);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--presets: ") + e.what());
    }
    const volume::CloudParams params = volume::cloud_from_json(doc.at("cloud"), name);
    for (int res : resolutions) {
      volume::GenerateOptions o;
      const volume::Aabb b = volume::CloudModel(params, 1.0, 0.0).bounds();
      const glm::dvec3 e = b.hi - b.lo;
      o.voxel_size = std::max({e.x, e.y, e.z}) / res;
      auto run = [&](bool sparse, bool limit, volume::GenerateStats& s) {
        o.sparse = sparse;
        o.octave_limit = limit;
        return volume::generate_density(params, o, &s);
      };
      const bool naive = res <= a.naive_max || name == a.naive_always;
      volume::GenerateStats s_full, s_lim, n_full, n_lim;
      const auto sparse_full = run(true, false, s_full);
      const auto sparse_lim = run(true, true, s_lim);
      const Diff limit_error = difference(*sparse_lim, *sparse_full);
      auto row = [&](const char* mode, const volume::GenerateStats& s, const std::string& err, const std::string& lim) {
        std::printf("| %s | %d | %.3g | %lld | %s | %d | %.3f | %.1f | %lld | %lld | %s | %s |\n", name.c_str(), res,
                    o.voxel_size, static_cast<long long>(s.voxels_in_bounds), mode, s.octaves_used, s.seconds,
                    double(s.voxels_in_bounds) / s.seconds * 1e-6, static_cast<long long>(s.noise_evaluations),
                    static_cast<long long>(s.active_voxels), err.c_str(), lim.c_str());
        std::fflush(stdout);
      };
      if (naive) {
        const auto naive_full = run(false, false, n_full);
        row("naive, all octaves (anchor)", n_full, "anchor", "-");
        row("sparse, all octaves", s_full, diff_text(difference(*sparse_full, *naive_full)), "-");
        const auto naive_lim = run(false, true, n_lim);
        row("naive, octave limit", n_lim, "anchor", diff_text(difference(*naive_lim, *naive_full)));
        row("**sparse, octave limit** (default)", s_lim, diff_text(difference(*sparse_lim, *naive_lim)),
            diff_text(limit_error));
      } else {
        row("sparse, all octaves", s_full, "(no naive run)", "-");
        row("**sparse, octave limit** (default)", s_lim, "(no naive run)", diff_text(limit_error));
      }
      // File: the default grid as half and as full float, written atomically.
      FileRow f{name, res, s_lim.active_voxels, 0, 0, 0, 0};
      for (bool half : {true, false}) {
        volume::ExportInfo info;
        info.preset = name;
        volume::ExportOptions eo;
        eo.half_float = half;
        const auto path = tmp / (name + (half ? ".half.vdb" : ".float.vdb"));
        const auto t0 = std::chrono::steady_clock::now();
        volume::write_volume_vdb(path, {sparse_lim}, info, eo);
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        (half ? f.half_bytes : f.float_bytes) = std::filesystem::file_size(path);
        (half ? f.half_s : f.float_s) = secs;
      }
      files.push_back(f);
    }
  }
  std::printf("\n### Files (the default grid, Blosc)\n\n| preset | N | active voxels | half: bytes | half: write s | float: bytes | float: write s | bytes per active voxel (half) |\n|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const FileRow& f : files)
    std::printf("| %s | %d | %lld | %ju | %.3f | %ju | %.3f | %.2f |\n", f.preset.c_str(), f.res,
                static_cast<long long>(f.active), f.half_bytes, f.half_s, f.float_bytes, f.float_s,
                f.active ? double(f.half_bytes) / double(f.active) : 0.0);
  std::vector<std::filesystem::path> written;
  for (const FileRow& f : files)
    if (f.res == files.back().res)  // the largest resolution's files
      for (const char* kind : {".half.vdb", ".float.vdb"}) written.push_back(tmp / (f.preset + kind));
  bench_reading(written, tmp, a.quick ? 1 : 3);
  if (a.field) bench_field(a.quick, tmp);
  std::filesystem::remove_all(tmp);
  if (a.keyframes > 0) bench_sky_keyframes(a.quick ? std::min(a.keyframes, 2) : a.keyframes);
  return 0;
}

}  // namespace

void add_bench_volume(CLI::App& bench, Action& action) {
  auto a = std::make_shared<BenchVolumeArgs>();
  CLI::App* cmd = bench.add_subcommand("volume", "Generation speed per preset against the naive every-voxel anchor");
  cmd->add_option("--presets", a->presets, "comma-separated preset names (default: all)");
  cmd->add_option("--res", a->res, "comma-separated resolutions (voxels across the largest extent)")->capture_default_str();
  cmd->add_option("--naive-max", a->naive_max, "run the slow naive anchor only up to this resolution")->capture_default_str();
  cmd->add_option("--naive-always", a->naive_always, "preset whose naive anchor runs at every resolution")->capture_default_str();
  cmd->add_flag("--quick", a->quick, "resolution 48, two presets, a 2 x 2 km field (smoke test)");
  cmd->add_flag("!--no-field", a->field, "skip the cumulus field section (10 x 10 km at 20 m)");
  cmd->add_option("--keyframes", a->keyframes, "keyframes of the default sky made as the viewer makes them and plainly (0: skip)")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  cmd->add_flag("--keyframes-only", a->keyframes_only, "only the sky keyframe section");
  cmd->callback([&action, a] { action = [a] { return run_bench_volume(*a); }; });
}

}  // namespace nimbus::cli
