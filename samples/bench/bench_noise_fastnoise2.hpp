// FastNoise2 as an anchor of `nimbus bench noise`: an optional build of its public source,
// loaded at run time through its C API (FastNoise_C.h) from a shared library the user names,
// never linked, downloaded or vendored. Its grids are timed on the same cube and clock as
// nimbus's rows, at a chosen maximum SIMD level.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "bench_noise_harness.hpp"
#include "nimbus/noise/noise.hpp"

namespace nimbus::cli::bench_noise {

// The three node graphs compared with nimbus: Perlin, 6-octave FractalFBm of Perlin
// (gain 0.5, lacunarity 2), and CellularDistance (F1, Euclidean). Feature scale 1: one
// lattice cell per input unit, as nimbus's frequency 1.
enum class Fn2Graph { Perlin, PerlinFbm6, CellularDistance };

class FastNoise2 {
 public:
  // Loads the library at `path`; throws std::runtime_error naming the path and what is missing.
  explicit FastNoise2(const std::string& path);
  ~FastNoise2();
  FastNoise2(const FastNoise2&) = delete;
  FastNoise2& operator=(const FastNoise2&) = delete;

  const std::string& path() const { return path_; }
  // Whether the library runs the given level on this CPU (its active feature set at that cap).
  bool supports(noise::SimdLevel level) const;
  // ns per sample of one thread's thread CPU time, best of `repeats`, for the graph on the grid
  // (cast to float, as its API takes), with the output's range.
  double time_grid(Fn2Graph graph, noise::SimdLevel level, const noise::GridSpec& grid, int repeats,
                   std::vector<float>& out) const;

 private:
  struct Api;
  std::string path_;
  void* handle_ = nullptr;
  std::unique_ptr<Api> api_;
  void* make(Fn2Graph graph, noise::SimdLevel level) const;
};

const char* fn2_graph_name(Fn2Graph graph);

// The section "FastNoise2 beside nimbus": for each spacing, the three graphs against nimbus's
// gradient 1-octave, gradient 6-octave fBm and Worley 1-octave rows at AVX2 and AVX-512 (those
// the CPU runs), timed alternately in the same run, with the ratio nimbus / FastNoise2.
void fastnoise2_rows(const FastNoise2& fn2, int64_t res, int repeats);

}  // namespace nimbus::cli::bench_noise
