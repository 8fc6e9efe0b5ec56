// `nimbus bench airlight`: nanoseconds per airlight evaluation beside its error against the double
// quadrature, for stable, table:N and raymarch:N on the CPU and through GLSL on an OpenGL context
// (the library's compute pass, render/shafts/airlight_gl.hpp, timed with glFinish +
// steady_clock); the quadrature's own time is the anchor.
#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>

#include "cli/cli.hpp"
#include "cli/render_args.hpp"
#include "nimbus/render/media/medium.hpp"
#include "nimbus/render/media/airlight.hpp"
#include "nimbus/render/gl/context.hpp"
#include "nimbus/render/shafts/airlight_gl.hpp"

namespace nimbus::cli {
namespace {

struct BenchAirlightArgs {
  int log2_n = 20;           // timed queries: 2^log2_n
  int error_queries = 8192;  // the first this many also get the quadrature (error columns)
  std::string methods = "stable,table:16,table:64,table:256,raymarch:16,raymarch:64,raymarch:256";
  std::string devices = "cpu,gl";
  std::string phase = "isotropic";
  int repeat = 3;
  bool quick = false;
};

// The target region: gamma in [1e-3, pi - 1e-3] log-dense toward both ends, beta Dsv in
// [1e-3, 50], beta Dvp in [1e-3, 1e4] (log) or infinite (one in eight), beta in {1, 1e-3, 37}.
std::vector<render::AirlightQuery> target_queries(size_t n) {
  std::mt19937_64 rng(20050731);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double betas[3] = {1.0, 1e-3, 37.0};
  std::vector<render::AirlightQuery> out(n);
  for (size_t i = 0; i < n; ++i) {
    const double side = u(rng), fg = u(rng), fs = u(rng), fv = u(rng), inf = u(rng);
    const double g = 1e-3 * std::pow(1.5e3, fg);
    const double beta = betas[i % 3];
    const double Tsv = 1e-3 * std::pow(5e4, fs);
    const double Tvp = inf < 0.125 ? std::numeric_limits<double>::infinity() : 1e-3 * std::pow(1e7, fv);
    out[i] = {beta, 1.0, Tsv / beta, Tvp / beta, side < 0.5 ? g : std::numbers::pi - g};
  }
  return out;
}

struct Row {
  std::string method, device;
  double ns = 0.0, compile_ms = -1.0, max_err = 0.0, rms_err = 0.0, median_err = 0.0;
};

void errors(Row& row, const std::vector<double>& got, const std::vector<double>& ref) {
  double sum2 = 0.0;
  std::vector<double> all(ref.size());
  for (size_t i = 0; i < ref.size(); ++i) {
    double e = std::abs(got[i] / ref[i] - 1.0);
    if (!std::isfinite(e)) e = std::numeric_limits<double>::infinity();
    row.max_err = std::max(row.max_err, e);
    sum2 += e * e;
    all[i] = e;
  }
  row.rms_err = std::sqrt(sum2 / double(ref.size()));
  std::nth_element(all.begin(), all.begin() + all.size() / 2, all.end());
  row.median_err = all[all.size() / 2];
}

template <class F>
double best_seconds(int repeat, F&& f) {
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

// Times one method on the GL context: compile (cold) + a one-query dispatch, then the best of
// `repeat` passes over all queries. Fills ns, compile_ms and the errors over the first ref.size().
void run_gl(Row& row, const render::AirlightMethod& m, const render::Phase& phase,
            const std::vector<render::AirlightQuery>& qs, const std::vector<double>& ref, int repeat) {
  // The library's evaluator (airlight_gl.hpp: shaders/airlight_eval.comp.glsl), the one the
  // program and the tests use. The nonce makes every run's program new to the driver's shader
  // cache, so that the compile is measured cold.
  render::AirlightGlEvaluator evaluator(qs, m, phase);
  static int nonce = int(std::chrono::steady_clock::now().time_since_epoch().count() % 1000000000);
  const std::string defines = "#define AL_NONCE " + std::to_string(++nonce) + "\n";
  glFinish();
  const auto t0 = std::chrono::steady_clock::now();
  evaluator.compile(defines);
  evaluator.evaluate(1);  // drivers that compile at first use (llvmpipe) do it here
  row.compile_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  evaluator.evaluate();  // warm-up
  const double s = best_seconds(repeat, [&] { evaluator.evaluate(); });
  row.ns = s * 1e9 / double(evaluator.size());
  errors(row, evaluator.results(int(ref.size())), ref);
}


std::string fmt(const char* f, double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

int run_bench_airlight(const BenchAirlightArgs& a) {
  if (a.log2_n < 6 || a.log2_n > 24) throw UsageError("--log2-n: must be in [6, 24] (got " + std::to_string(a.log2_n) + ")");
  if (a.error_queries < 1 || a.error_queries > (1 << a.log2_n))
    throw UsageError("--error-queries: must be in [1, 2^log2-n] (got " + std::to_string(a.error_queries) + ")");
  if (a.repeat < 1 || a.repeat > 100) throw UsageError("--repeat: must be in [1, 100] (got " + std::to_string(a.repeat) + ")");
  const int log2_n = a.quick ? 12 : a.log2_n;
  const int n_err = a.quick ? 512 : a.error_queries;
  const int repeat = a.quick ? 1 : a.repeat;
  render::Phase phase;
  try {
    phase = render::parse_medium_phase(a.phase);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--phase: ") + e.what());
  }
  std::vector<render::AirlightMethod> methods;
  for (const std::string& m : split_list(a.methods)) {
    try {
      methods.push_back(render::parse_airlight_method(m));
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--methods: ") + e.what());
    }
    if (methods.back().kind == render::AirlightMethod::Quadrature)
      throw UsageError("--methods: quadrature is always measured (the anchor)");
    if (methods.back().kind == render::AirlightMethod::Table && phase.kind != render::PhaseKind::Isotropic)
      throw UsageError("--methods: " + m + " is isotropic only; drop it or use --phase isotropic");
  }
  bool cpu = false, gl = false;
  for (const std::string& d : split_list(a.devices)) {
    if (d == "cpu") cpu = true;
    else if (d == "gl") gl = true;
    else throw UsageError("--devices: expected cpu and/or gl (got '" + d + "')");
  }

  const size_t n = size_t(1) << log2_n;
  const auto qs = target_queries(n);
  const std::vector<render::AirlightQuery> err_qs(qs.begin(), qs.begin() + n_err);
  std::vector<Row> rows;
  std::vector<double> ref;
  {
    Row row{"quadrature", "cpu"};
    const double s = best_seconds(1, [&] { ref = render::evaluate_airlight(err_qs, {render::AirlightMethod::Quadrature, 0}, phase); });
    row.ns = s * 1e9 / double(n_err);
    rows.push_back(row);
  }
  std::printf("nimbus bench airlight: %zu queries (timing), the first %d against the quadrature (error); phase %s\n", n,
              n_err, render::to_string(phase).c_str());
  if (cpu)
    for (const auto& m : methods) {
      Row row{render::to_string(m), "cpu"};
      // Long ray marches are timed on the error queries only (a random subset of the same grid).
      const auto& timed = m.kind == render::AirlightMethod::RayMarch && m.n > 64 ? err_qs : qs;
      std::vector<double> got(timed.size());
      if (m.kind == render::AirlightMethod::Table) {  // the table is built once, outside the timing
        const render::FTable table(m.n);
        const double s = best_seconds(repeat, [&] {
          for (size_t i = 0; i < timed.size(); ++i) got[i] = render::airlight_table(timed[i], table);
        });
        row.ns = s * 1e9 / double(timed.size());
      } else {
        const double s = best_seconds(repeat, [&] { got = render::evaluate_airlight(timed, m, phase); });
        row.ns = s * 1e9 / double(timed.size());
      }
      errors(row, std::vector<double>(got.begin(), got.begin() + n_err), ref);
      rows.push_back(row);
    }
  std::string device_name;
  if (gl) {
    std::unique_ptr<render::GlContext> context;
    try {
      context = render::GlContext::create_headless();
    } catch (const render::GlUnavailable& e) {
      std::fprintf(stderr, "nimbus: no GL rows: %s\n", e.what());
    }
    if (context) {
      device_name = context->renderer();
      for (const auto& m : methods) {
        Row row{render::to_string(m), "gl"};
        run_gl(row, m, phase, qs, ref, repeat);
        rows.push_back(row);
      }
    }
  }
  if (!device_name.empty()) std::printf("gl: %s\n", device_name.c_str());
  std::printf("| method | device | ns per evaluation | compile ms (cold) | max rel. error | RMS rel. error | median |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (const Row& r : rows) {
    const bool anchor = r.method == "quadrature";
    std::printf("| %s | %s | %s | %s | %s | %s | %s |\n", r.method.c_str(), r.device.c_str(), fmt("%.3g", r.ns).c_str(),
                r.compile_ms < 0 ? "-" : fmt("%.0f", r.compile_ms).c_str(), anchor ? "(reference)" : fmt("%.2g", r.max_err).c_str(),
                anchor ? "-" : fmt("%.2g", r.rms_err).c_str(), anchor ? "-" : fmt("%.2g", r.median_err).c_str());
  }
  return 0;
}

}  // namespace

void add_bench_airlight(CLI::App& bench, Action& action) {
  auto a = std::make_shared<BenchAirlightArgs>();
  CLI::App* cmd = bench.add_subcommand(
      "airlight", "ns per airlight evaluation (CPU and GL) beside its error against the double quadrature");
  cmd->add_option("--log2-n", a->log2_n, "2^N timed queries over the target grid (6..24)")->capture_default_str();
  cmd->add_option("--error-queries", a->error_queries, "the first this many are compared with the quadrature")
      ->capture_default_str();
  cmd->add_option("--methods", a->methods, "comma-separated: stable, table:N, raymarch:N")->capture_default_str();
  cmd->add_option("--devices", a->devices, "cpu, gl or both")->capture_default_str();
  cmd->add_option("--phase", a->phase, "isotropic, hg:G, schlick:G or rayleigh")->capture_default_str();
  cmd->add_option("--repeat", a->repeat, "timed passes per row; the best is kept")->capture_default_str();
  cmd->add_flag("--quick", a->quick, "smoke test: 2^12 queries, 512 compared, one pass");
  cmd->callback([&action, a] { action = [a] { return run_bench_airlight(*a); }; });
}

}  // namespace nimbus::cli
