// Batched evaluation of a NoiseField over regular grids and point arrays: one kernel source
// compiled for the scalar path, SSE4.1, AVX2 and AVX-512, picked at run time, and spread
// over threads with TBB. Every level gives the same bits as NoiseField::eval. evaluate_grid polls
// the stop token of the call it runs in (nimbus/base/cancel.hpp) every block of about 4096 samples.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "nimbus/noise/field.hpp"

namespace nimbus::noise {

enum class SimdLevel { Scalar, Sse41, Avx2, Avx512 };

std::string_view to_string(SimdLevel level);
std::optional<SimdLevel> parse_simd_level(std::string_view s);
bool simd_level_supported(SimdLevel level);
// The widest level this CPU runs; the environment variable NIMBUS_SIMD=scalar|sse4.1|avx2|avx512
// lowers it (never raises it above what the CPU supports).
SimdLevel best_simd_level();

// Samples at origin + spacing * (i, j, k), x fastest, in input units.
struct GridSpec {
  std::array<double, 3> origin{0.0, 0.0, 0.0};
  double spacing = 1.0;
  std::array<int64_t, 3> res{1, 1, 1};
  int64_t count() const { return res[0] * res[1] * res[2]; }
  std::array<double, 3> point(int64_t i, int64_t j, int64_t k) const {
    return {origin[0] + double(i) * spacing, origin[1] + double(j) * spacing,
            origin[2] + double(k) * spacing};
  }
};

struct BatchOptions {
  std::optional<SimdLevel> simd;  // default: best_simd_level()
  bool parallel = true;           // TBB over rows or point blocks
};

// out.size() must equal grid.count(); throws std::invalid_argument otherwise.
void evaluate_grid(const NoiseField& field, const GridSpec& grid, std::span<float> out,
                   const BatchOptions& options = {});

void evaluate_points(const NoiseField& field, std::span<const std::array<double, 3>> points,
                     std::span<float> out, const BatchOptions& options = {});

// Whether two fields read one lattice at every octave: the same kind (not wavelet), octave
// count, octave frequencies and periods. Seeds, gains and times may differ.
bool shares_lattice(const NoiseField& a, const NoiseField& b);

// Several fields at the same points: outs[f] gets exactly evaluate_points(*fields[f], ...).
// When every field shares_lattice with the first, each point is split into lattice cells once
// for all of them (the three displacement noises of a cloud model, say); otherwise they are
// evaluated one after the other. Throws std::invalid_argument on a null field, a count of outs
// that is not the count of fields, or an out whose size is not the count of points.
void evaluate_points(std::span<const NoiseField* const> fields, std::span<const std::array<double, 3>> points,
                     std::span<const std::span<float>> outs, const BatchOptions& options = {});

}  // namespace nimbus::noise
