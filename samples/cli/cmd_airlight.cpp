// `nimbus airlight --method table:N|stable|raymarch:N|quadrature [--device cpu|gl] [--phase P]`:
// Sun et al.'s airlight for CSV rows `beta,I0,Dsv,Dvp,gamma` read from stdin (Dvp may be inf),
// one La per line (%.9g). A malformed row is a usage error (exit 2) naming its line and field;
// stdin is read within the input limits (base/input_limits.hpp: 4096 bytes a line, 1,000,000
// lines, 64 MiB), so /dev/zero or an endless pipe fails at once instead of filling memory.
#include <charconv>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "cli.hpp"
#include "nimbus/base/input_limits.hpp"
#include "nimbus/render/media/medium.hpp"
#include "nimbus/render/media/airlight.hpp"
#include "nimbus/render/shafts/airlight_gl.hpp"

namespace nimbus::cli {
namespace {

struct AirlightOptions {
  std::string method = "stable";
  std::string device = "cpu";
  std::string phase = "isotropic";
};

constexpr const char* kFields[5] = {"beta", "I0", "Dsv", "Dvp", "gamma"};

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

render::AirlightQuery parse_row(const std::string& line, long number) {
  const std::string where = "stdin line " + std::to_string(number);
  std::vector<std::string> fields;
  size_t start = 0;
  while (true) {
    const auto comma = line.find(',', start);
    fields.push_back(trim(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (fields.size() != 5)
    throw UsageError(where + ": expected 5 fields beta,I0,Dsv,Dvp,gamma, got " + std::to_string(fields.size()));
  double v[5];
  for (int k = 0; k < 5; ++k) {
    const std::string& f = fields[k];
    const char* first = f.data();
    const char* last = first + f.size();
    const auto r = std::from_chars(first, last, v[k]);
    if (f.empty() || r.ec != std::errc() || r.ptr != last)
      throw UsageError(where + ", field " + kFields[k] + ": '" + echo(f) + "' is not a number");
  }
  render::AirlightQuery q{v[0], v[1], v[2], v[3], v[4]};
  try {
    render::validate(q);
  } catch (const std::invalid_argument& e) {
    throw UsageError(where + ", field " + e.what());
  }
  return q;
}

int run_airlight(const AirlightOptions& o) {
  render::AirlightMethod method;
  try {
    method = render::parse_airlight_method(o.method);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--method: ") + e.what());
  }
  if (o.device == "gl" && method.kind == render::AirlightMethod::Quadrature)
    throw UsageError("--method quadrature is CPU only (double precision); use --device cpu");
  render::Phase phase;
  try {
    phase = render::parse_medium_phase(o.phase);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--phase: ") + e.what());
  }
  if (method.kind == render::AirlightMethod::Table && phase.kind != render::PhaseKind::Isotropic)
    throw UsageError("--phase " + o.phase + ": the table method is isotropic only (Sun's F(u, v))");
  std::vector<render::AirlightQuery> queries;
  std::string line;
  long number = 0;
  std::size_t bytes = 0;
  for (;;) {
    const LineRead r = read_line_limited(std::cin, line, kMaxStdinLineBytes);
    if (r == LineRead::End) break;
    ++number;
    if (r == LineRead::TooLong)
      throw UsageError("stdin line " + std::to_string(number) + ": longer than " + std::to_string(kMaxStdinLineBytes) +
                       " bytes (a row is beta,I0,Dsv,Dvp,gamma)");
    if (static_cast<std::size_t>(number) > kMaxStdinLines)
      throw UsageError("stdin: more than " + std::to_string(kMaxStdinLines) + " rows; split the input");
    bytes += line.size() + 1;
    if (bytes > kMaxStdinBytes) throw UsageError("stdin: more than " + std::to_string(kMaxStdinBytes >> 20) + " MiB; split the input");
    queries.push_back(parse_row(line, number));
  }
  const std::vector<double> la =
      o.device == "gl" ? render::evaluate_airlight_gl(queries, method, phase) : render::evaluate_airlight(queries, method, phase);
  for (double v : la) std::printf("%.9g\n", v);
  return 0;
}

}  // namespace

void add_airlight_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<AirlightOptions>();
  CLI::App* cmd = app.add_subcommand(
      "airlight", "Airlight of a point light (Sun et al. 2005) for CSV rows beta,I0,Dsv,Dvp,gamma on stdin");
  cmd->add_option("--method", o->method, "quadrature (double reference), stable (float32 shader code), table:N, raymarch:N")
      ->capture_default_str();
  cmd->add_option("--device", o->device, "cpu, or gl: evaluate the GLSL functions on an OpenGL 4.5 context")
      ->check(CLI::IsMember({"cpu", "gl"}))
      ->capture_default_str();
  cmd->add_option("--phase", o->phase,
                  "isotropic, hg:G, schlick:G or rayleigh: replaces Sun's 1/(4 pi) (stable, raymarch:N, quadrature)")
      ->capture_default_str();
  cmd->callback([&action, o] { action = [o] { return run_airlight(*o); }; });
}

}  // namespace nimbus::cli
