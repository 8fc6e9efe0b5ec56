// Run-time choice of the instruction-set level, and threading over rows and point blocks.
#include "nimbus/noise/batch.hpp"

#include "nimbus/base/cancel.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "batch_level.hpp"

namespace nimbus::noise {

std::string_view to_string(SimdLevel level) {
  switch (level) {
    case SimdLevel::Scalar: return "scalar";
    case SimdLevel::Sse41: return "sse4.1";
    case SimdLevel::Avx2: return "avx2";
    case SimdLevel::Avx512: return "avx512";
  }
  return "?";
}

std::optional<SimdLevel> parse_simd_level(std::string_view s) {
  for (SimdLevel l : {SimdLevel::Scalar, SimdLevel::Sse41, SimdLevel::Avx2, SimdLevel::Avx512})
    if (s == to_string(l)) return l;
  return std::nullopt;
}

bool simd_level_supported(SimdLevel level) {
  __builtin_cpu_init();
  switch (level) {
    case SimdLevel::Scalar: return true;
    case SimdLevel::Sse41: return __builtin_cpu_supports("sse4.1");
    case SimdLevel::Avx2: return __builtin_cpu_supports("avx2");
    case SimdLevel::Avx512:
      return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
             __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw");
  }
  return false;
}

SimdLevel best_simd_level() {
  SimdLevel best = SimdLevel::Scalar;
  for (SimdLevel l : {SimdLevel::Sse41, SimdLevel::Avx2, SimdLevel::Avx512})
    if (simd_level_supported(l)) best = l;
  if (const char* env = std::getenv("NIMBUS_SIMD")) {
    if (auto want = parse_simd_level(env); want && int(*want) < int(best)) best = *want;
  }
  return best;
}

namespace {

level::Kernels kernels_for(const BatchOptions& o) {
  const SimdLevel l = o.simd.value_or(best_simd_level());
  if (!simd_level_supported(l))
    throw std::invalid_argument("SIMD level " + std::string(to_string(l)) + " is not supported by this CPU");
  switch (l) {
    case SimdLevel::Scalar: return level::scalar();
    case SimdLevel::Sse41: return level::sse41();
    case SimdLevel::Avx2: return level::avx2();
    case SimdLevel::Avx512: return level::avx512();
  }
  return level::scalar();
}

}  // namespace

void evaluate_grid(const NoiseField& field, const GridSpec& grid, std::span<float> out,
                   const BatchOptions& options) {
  for (int a = 0; a < 3; ++a)
    if (grid.res[a] < 1) throw std::invalid_argument("grid resolution must be >= 1 on every axis");
  if (!std::isfinite(grid.spacing) || grid.spacing <= 0.0)
    throw std::invalid_argument("grid spacing must be finite and > 0");
  if (static_cast<int64_t>(out.size()) != grid.count())
    throw std::invalid_argument("output holds " + std::to_string(out.size()) + " values, grid has " +
                                std::to_string(grid.count()));
  const level::Kernels k = kernels_for(options);
  const detail::FieldData& fd = field.data();
  const int64_t rows = grid.res[1] * grid.res[2];
  // The call's stop (cancel.hpp) is polled every block of about 4096 samples: a grid of 512^3
  // Worley samples at 8 octaves takes seconds, a block a fraction of a millisecond.
  const std::stop_token stop = current_stop_token();
  const int64_t grain = std::max<int64_t>(1, 4096 / grid.res[0]);
  // Rows [begin, end) a grain at a time, polling between grains. TBB's auto partitioner hands a
  // task many grains at once, so a poll per task could wait for seconds.
  const auto rows_polled = [&](int64_t begin, int64_t end) {
    for (int64_t b = begin; b < end; b += grain) {
      throw_if_stopped(stop);
      k.rows(fd, grid, b, std::min(end, b + grain), out.data());
    }
  };
  if (!options.parallel) return rows_polled(0, rows);
  tbb::parallel_for(tbb::blocked_range<int64_t>(0, rows, grain),
                    [&](const tbb::blocked_range<int64_t>& r) { rows_polled(r.begin(), r.end()); });
}

void evaluate_points(const NoiseField& field, std::span<const std::array<double, 3>> points,
                     std::span<float> out, const BatchOptions& options) {
  if (out.size() != points.size())
    throw std::invalid_argument("output holds " + std::to_string(out.size()) + " values for " +
                                std::to_string(points.size()) + " points");
  const level::Kernels k = kernels_for(options);
  const detail::FieldData& fd = field.data();
  if (!options.parallel) {
    k.points(fd, points.data(), points.size(), out.data());
    return;
  }
  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 4096),
                    [&](const tbb::blocked_range<size_t>& r) {
                      k.points(fd, points.data() + r.begin(), r.size(), out.data() + r.begin());
                    });
}

bool shares_lattice(const NoiseField& a, const NoiseField& b) {
  const detail::FieldData& x = a.data();
  const detail::FieldData& y = b.data();
  if (x.kind != y.kind || x.kind == Kind::Wavelet || x.octaves != y.octaves) return false;
  for (int o = 0; o < x.octaves; ++o)
    for (int ax = 0; ax < 3; ++ax)
      if (x.oct[o].freq != y.oct[o].freq || x.oct[o].period[ax] != y.oct[o].period[ax] ||
          x.oct[o].iperiod[ax] != y.oct[o].iperiod[ax])
        return false;
  return true;
}

void evaluate_points(std::span<const NoiseField* const> fields, std::span<const std::array<double, 3>> points,
                     std::span<const std::span<float>> outs, const BatchOptions& options) {
  if (outs.size() != fields.size())
    throw std::invalid_argument(std::to_string(outs.size()) + " outputs for " + std::to_string(fields.size()) + " fields");
  for (size_t f = 0; f < fields.size(); ++f) {
    if (!fields[f]) throw std::invalid_argument("field " + std::to_string(f) + " is null");
    if (outs[f].size() != points.size())
      throw std::invalid_argument("output " + std::to_string(f) + " holds " + std::to_string(outs[f].size()) +
                                  " values for " + std::to_string(points.size()) + " points");
  }
  bool shared = !fields.empty();
  for (size_t f = 1; f < fields.size() && shared; ++f) shared = shares_lattice(*fields[0], *fields[f]);
  if (!shared) {
    for (size_t f = 0; f < fields.size(); ++f) evaluate_points(*fields[f], points, outs[f], options);
    return;
  }
  const level::Kernels k = kernels_for(options);
  // Pointer tables on the stack for a few fields (callers evaluating leaf blocks serially call
  // this often), else on the heap.
  constexpr size_t kFew = 8;
  const size_t nf = fields.size();
  std::array<const detail::FieldData*, kFew> fd_few{};
  std::vector<const detail::FieldData*> fd_many(nf > kFew ? nf : 0);
  const detail::FieldData** fds = nf > kFew ? fd_many.data() : fd_few.data();
  for (size_t f = 0; f < nf; ++f) fds[f] = &fields[f]->data();
  auto run = [&](size_t begin, size_t n) {
    std::array<float*, kFew> out_few{};
    std::vector<float*> out_many(nf > kFew ? nf : 0);
    float** out = nf > kFew ? out_many.data() : out_few.data();
    for (size_t f = 0; f < nf; ++f) out[f] = outs[f].data() + begin;
    k.shared_points(fds, nf, points.data() + begin, n, out);
  };
  if (!options.parallel) {
    run(0, points.size());
    return;
  }
  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 4096),
                    [&](const tbb::blocked_range<size_t>& r) { run(r.begin(), r.size()); });
}

}  // namespace nimbus::noise
