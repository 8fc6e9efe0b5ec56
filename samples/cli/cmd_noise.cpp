// `nimbus noise`: samples one noise field on a cube and writes it as a dense OpenVDB grid
// named "noise" whose voxel size is the sample spacing in lattice units.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "cli.hpp"
#include "noise_request.hpp"
#include "outputs.hpp"
#include "nimbus/noise/noise.hpp"
#include "nimbus/volume/vdb_io.hpp"

namespace nimbus::cli {
namespace {

int run_noise(const NoiseOptions& o) {
  if (o.res < 1 || o.res > 4096) throw UsageError("--res: " + std::to_string(o.res) + " must be in [1, 4096]");
  if (o.output.empty()) throw UsageError("-o: an output file is required");
  noise::NoiseParams p = plan_noise(o);
  noise::BatchOptions batch;
  if (!o.simd.empty()) {
    batch.simd = noise::parse_simd_level(o.simd);
    if (!batch.simd) throw UsageError("--simd: unknown level '" + o.simd + "' (scalar, sse4.1, avx2, avx512)");
    if (!noise::simd_level_supported(*batch.simd)) throw UsageError("--simd: " + o.simd + " is not supported by this CPU");
  }
  // The cube [0, 1)^3 is sampled res times per axis: spacing 1/res input units, and
  // frequency/res lattice units.
  const double spacing = 1.0 / double(o.res);
  noise::OctaveChoice choice{};
  if (o.auto_octaves) p = noise::limit_octaves(p, spacing, &choice);

  check_outputs({{"-o", o.output}});
  const int64_t count = o.res * o.res * o.res;
  ensure_fits_in_memory(uint64_t(count), 12, "a " + std::to_string(o.res) + "^3 noise grid");
  const auto t0 = std::chrono::steady_clock::now();
  const noise::NoiseField field(p);
  std::vector<float> values(static_cast<size_t>(count));
  noise::GridSpec grid;
  grid.spacing = spacing;
  grid.res = {o.res, o.res, o.res};
  noise::evaluate_grid(field, grid, values, batch);
  const auto t1 = std::chrono::steady_clock::now();

  volume::DenseGridDesc desc;
  desc.name = "noise";
  desc.res = grid.res;
  desc.voxel_size = p.frequency * spacing;  // sample spacing in lattice units
  desc.metadata = {{"creator", std::string("nimbus ") + NIMBUS_VERSION},
                   {"nimbus_noise_kind", std::string(noise::to_string(p.kind))},
                   {"nimbus_fractal", std::string(noise::to_string(p.fractal))},
                   {"nimbus_octaves", int64_t(p.fractal == noise::Fractal::None ? 1 : p.octaves)},
                   {"nimbus_frequency", p.frequency},
                   {"nimbus_lacunarity", p.lacunarity},
                   {"nimbus_gain", p.gain},
                   {"nimbus_seed", int64_t(p.seed)},
                   {"nimbus_projected", int64_t(p.projected)},
                   {"nimbus_range_min", double(field.range().lo)},
                   {"nimbus_range_max", double(field.range().hi)}};
  if (p.time) desc.metadata.push_back({"nimbus_time", *p.time});
  volume::write_dense_vdb(o.output, desc, values);
  float lo = values[0], hi = values[0];
  double sum = 0.0, sum2 = 0.0;
  for (float v : values) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    sum += v;
    sum2 += double(v) * v;
  }
  const double mean = sum / double(count);
  const double sd = std::sqrt(std::max(0.0, sum2 / double(count) - mean * mean));
  const double secs = std::chrono::duration<double>(t1 - t0).count();
  std::printf("wrote %s: %s %s noise, %lld^3 samples, voxel size %g lattice units, octaves %d",
              o.output.c_str(), std::string(noise::to_string(p.fractal)).c_str(),
              std::string(noise::to_string(p.kind)).c_str(), static_cast<long long>(o.res),
              desc.voxel_size, p.fractal == noise::Fractal::None ? 1 : p.octaves);
  if (o.auto_octaves)
    std::printf(" (footprint limit: %d of %d; Nyquist %g cycles/unit)", choice.octaves,
                choice.requested, choice.nyquist);
  std::printf("\n  values in [%.4f, %.4f] (documented range [%g, %g]), mean %.4f, sd %.4f", lo, hi,
              double(field.range().lo), double(field.range().hi), mean, sd);
  if (const double e = field.expected_sd(); std::isfinite(e)) std::printf(" (predicted %.4f)", e);
  std::printf("; evaluated in %.3f s (%s)\n", secs,
              std::string(noise::to_string(batch.simd.value_or(noise::best_simd_level()))).c_str());
  return 0;
}

}  // namespace

void add_noise_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<NoiseOptions>();
  CLI::App* cmd = app.add_subcommand("noise", "Sample a noise field on the unit cube and write it as OpenVDB");
  cmd->add_option("--kind", o->kind, "value, gradient, wavelet or worley")->capture_default_str();
  cmd->add_flag("--projected", o->projected, "wavelet: evaluate 3D noise projected onto z slices");
  cmd->add_option("--fractal", o->fractal, "none, fbm, turbulence or ridged")->capture_default_str();
  cmd->add_option("--octaves", o->octaves, "octaves of the fractal sum")->capture_default_str();
  cmd->add_option("--frequency", o->frequency, "lattice cycles across the cube, first octave")->capture_default_str();
  cmd->add_option("--lacunarity", o->lacunarity, "frequency ratio between octaves")->capture_default_str();
  cmd->add_option("--gain", o->gain, "amplitude ratio between octaves")->capture_default_str();
  cmd->add_option("--res", o->res, "samples per axis")->capture_default_str();
  cmd->add_option("--seed", o->seed, "random seed")->capture_default_str();
  cmd->add_option("--time", o->time, "animation time in lattice units (animated noise)");
  cmd->add_option("--period", o->period, "integer period in lattice units on every axis (0: none)")->capture_default_str();
  cmd->add_flag("--auto-octaves", o->auto_octaves, "drop octaves above the Nyquist limit of the grid");
  cmd->add_option("--simd", o->simd, "scalar, sse4.1, avx2 or avx512 (default: best available)");
  cmd->add_option("-o,--output", o->output, "output .vdb file")->required();
  cmd->callback([&action, o] { action = [o] { return run_noise(*o); }; });
}

}  // namespace nimbus::cli
