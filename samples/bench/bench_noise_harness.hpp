// The harness of `nimbus bench noise` (bench_noise.cpp): its clocks, its table cells (times,
// ranges, the SIMD paths' difference from the scalar path) and the machine's description.
#pragma once
#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "nimbus/noise/noise.hpp"

namespace nimbus::cli::bench_noise {

double thread_cpu_seconds();  // this thread's CPU time
double wall_seconds();        // steady clock

// Best (smallest) time of `repeats` calls of f, measured with `clock`.
template <class F>
double best_of(int repeats, double (*clock)(), F&& f) {
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < repeats; ++r) {
    const double t0 = clock();
    f();
    best = std::min(best, clock() - t0);
  }
  return best;
}

std::string fmt(const char* format, double v);  // one number through printf's format
std::string ns_cell(double ns);                 // ns/sample, 2 or 1 decimals
std::string ms_cell(double ns);                 // Msamples/s from ns/sample

struct MinMax {
  float lo = std::numeric_limits<float>::infinity();
  float hi = -std::numeric_limits<float>::infinity();
};

MinMax min_max(const std::vector<float>& v);
std::string range_cell(MinMax m);  // "[lo, hi]"

// Error of a path against the scalar path: "0 (bit-identical)" when every bit matches.
std::string diff_cell(const std::vector<float>& ref, const std::vector<float>& got);

// A row of the table: nimbus's scalar and SIMD paths, or an anchor (no SIMD cells).
struct Cell {
  double ns = 0.0;
  std::string diff;  // against the scalar path
};

struct Row {
  std::string name;
  std::string grid_note;          // empty: the spacing's cube
  double scalar_ns = 0.0;
  std::vector<Cell> simd;         // one per measured SIMD level, same order as `levels`
  std::string observed, documented;
};

// The table of one spacing's rows, a column pair per SIMD level.
void print_rows(const std::vector<Row>& rows, const std::vector<noise::SimdLevel>& levels);

std::string cpu_model();      // /proc/cpuinfo's model name
std::string load_average();   // /proc/loadavg's 1/5/15 minutes
std::string utc_now();        // "YYYY-MM-DD HH:MM UTC"
std::string harness_flags();  // how the bench sources were compiled

}  // namespace nimbus::cli::bench_noise
