// The harness of `nimbus bench noise` (bench_noise_harness.hpp).
#include "bench_noise_harness.hpp"

#include <time.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>

namespace nimbus::cli::bench_noise {

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

std::string ns_cell(double ns) { return ns < 10.0 ? fmt("%.2f", ns) : fmt("%.1f", ns); }
std::string ms_cell(double ns) {  // Msamples/s from ns/sample
  const double m = 1e3 / ns;
  return m < 10.0 ? fmt("%.2f", m) : fmt("%.1f", m);
}

MinMax min_max(const std::vector<float>& v) {
  MinMax m;
  for (float x : v) {
    m.lo = std::min(m.lo, x);
    m.hi = std::max(m.hi, x);
  }
  return m;
}

std::string range_cell(MinMax m) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "[%.3f, %.3f]", double(m.lo), double(m.hi));
  return buf;
}

std::string diff_cell(const std::vector<float>& ref, const std::vector<float>& got) {
  if (ref.size() == got.size() && std::memcmp(ref.data(), got.data(), ref.size() * sizeof(float)) == 0)
    return "0 (bit-identical)";
  double worst = 0.0;
  size_t nan_mismatch = 0;
  for (size_t i = 0; i < ref.size(); ++i) {
    if (std::isnan(ref[i]) != std::isnan(got[i])) ++nan_mismatch;
    else if (!std::isnan(ref[i])) worst = std::max(worst, std::fabs(double(ref[i]) - double(got[i])));
  }
  std::string s = "**max |diff| " + fmt("%.3g", worst) + "** (NOT bit-identical";
  if (nan_mismatch) s += ", " + std::to_string(nan_mismatch) + " NaN mismatches";
  return s + ")";
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) {
        auto s = line.substr(colon + 1);
        s.erase(0, s.find_first_not_of(' '));
        return s;
      }
    }
  }
  return "unknown CPU";
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  double a = 0, b = 0, c = 0;
  if (!(in >> a >> b >> c)) return "unknown";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.2f %.2f %.2f", a, b, c);
  return buf;
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", &tm);
  return buf;
}

// How the bench sources (the harness and the header-only glm anchor) were compiled. The
// noise library has its own flags (noise/CMakeLists.txt: -ffp-contract=off, one TU per ISA);
// libnoise is Debian's prebuilt shared library.
std::string harness_flags() {
  std::string s;
#if defined(__OPTIMIZE__)
  s += "optimised (__OPTIMIZE__)";
#else
  s += "NOT optimised (-O0)";
#endif
#if defined(NDEBUG)
  s += ", NDEBUG";
#else
  s += ", assertions on";
#endif
#if defined(__AVX512F__)
  s += ", -mavx512f or -march=native";
#elif defined(__AVX2__)
  s += ", -mavx2";
#else
  s += ", baseline x86-64 (no -march)";
#endif
#if defined(__FMA__)
  s += ", FMA";
#endif
#if defined(__FAST_MATH__)
  s += ", -ffast-math";
#endif
  return s + "; build type: see CMAKE_BUILD_TYPE";
}

void print_rows(const std::vector<Row>& rows, const std::vector<noise::SimdLevel>& levels) {
  std::printf("| Noise | scalar ns/sample | scalar Msamples/s |");
  for (noise::SimdLevel l : levels) {
    const std::string n(noise::to_string(l));
    std::printf(" %s ns/sample | %s Msamples/s |", n.c_str(), n.c_str());
  }
  std::printf(" SIMD output vs scalar (max \\|diff\\|) | observed range | documented range |\n|---|---:|---:|");
  for (size_t i = 0; i < levels.size(); ++i) std::printf("---:|---:|");
  std::printf("---|---|---|\n");
  for (const Row& r : rows) {
    std::string name = r.name;
    if (!r.grid_note.empty()) name += " (" + r.grid_note + ")";
    std::printf("| %s | %s | %s |", name.c_str(), ns_cell(r.scalar_ns).c_str(), ms_cell(r.scalar_ns).c_str());
    std::string diff;
    if (r.simd.empty()) {
      for (size_t i = 0; i < levels.size(); ++i) std::printf(" — | — |");
      diff = "n/a (anchor, own scalar code)";
    } else {
      for (size_t i = 0; i < r.simd.size(); ++i) {
        const Cell& c = r.simd[i];
        std::printf(" %s | %s |", ns_cell(c.ns).c_str(), ms_cell(c.ns).c_str());
        if (c.diff != "0 (bit-identical)")  // name each level that differs
          diff += (diff.empty() || diff == "0 (bit-identical)" ? "" : "; ") + std::string(noise::to_string(levels[i])) + ": " + c.diff;
        else if (diff.empty())
          diff = c.diff;
      }
    }
    std::printf(" %s | %s | %s |\n", diff.c_str(), r.observed.c_str(), r.documented.c_str());
  }
}

}  // namespace nimbus::cli::bench_noise
