// `nimbus view`: the interactive animated sky (a GLFW window with a Dear ImGui panel), or a
// scripted run of the same loop in a window or headless (--script, --headless).
#include <epoxy/gl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "cli/cli.hpp"
#include "cli/outputs.hpp"
#include "nimbus/base/input_limits.hpp"
#include "nimbus/base/output_path.hpp"
#include "nimbus/app/sequence_path.hpp"
#include "cli/render_args.hpp"
#include "nimbus/render/sky/sky_keyframes.hpp"
#include "nimbus/render/sky/view_state.hpp"
#include "nimbus/render/gl/context.hpp"
#include "nimbus/volume/preset.hpp"
#include "view_script.hpp"
#include "view_window.hpp"
#include "viewer.hpp"

namespace nimbus::cli {

using app::check_sequence_pattern;
using app::has_frame_field;
namespace {

struct ViewArgs {
  std::vector<std::string> files, presets;
  std::string scene, grid, up = "auto";
  std::string sky, state, script, screenshot_dir = ".", shader_dir, size = "960x540", state_out;
  bool headless = false, no_adaptive = false, no_temporal = false;
  double budget_ms = 100.0;
  int samples = 32;
};

// The shaders of the source tree this binary was built from, when it is still there (F5).
std::string source_shader_dir() {
#ifdef NIMBUS_SOURCE_SHADER_DIR
  std::error_code ec;
  if (std::filesystem::is_directory(NIMBUS_SOURCE_SHADER_DIR, ec)) return NIMBUS_SOURCE_SHADER_DIR;
#endif
  return {};
}

int run_view(const ViewArgs& a) {
  // Every flag before any work.
  const auto [width, height] = parse_resolution("--size", a.size);
  if (a.headless && a.script.empty()) throw UsageError("--headless: needs --script (a window is what the interactive viewer is)");
  if (!(a.budget_ms > 0.0 && a.budget_ms <= 100000.0)) throw UsageError("--budget-ms: must be in (0, 100000]");
  if (a.samples < 1 || a.samples > 4096) throw UsageError("--samples: must be in [1, 4096], got " + std::to_string(a.samples));
  if ((!a.sky.empty()) + (!a.presets.empty()) + (!a.files.empty()) > 1)
    throw UsageError("FILE.vdb, --preset and --sky: give one of them");
  if (a.up != "auto" && a.up != "y" && a.up != "z") throw UsageError("--up-axis: '" + a.up + "' must be auto, y or z");
  for (const std::string& f : a.files)
    if (!check_sequence_pattern("FILE", f).has_field) refuse_special_file(f, "FILE");
  if (!a.shader_dir.empty() && !std::filesystem::is_directory(a.shader_dir))
    throw UsageError("--shader-dir: '" + a.shader_dir + "' is not a folder");
  for (const std::string& p : a.presets) {
    try {
      volume::load_preset(p);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--preset: ") + e.what());
    }
  }
  int version = render::kViewStateVersion;
  render::ViewState state = a.state.empty() ? render::default_view_state() : render::load_view_state(a.state, &version);
  const std::string version_note = render::view_state_version_note(a.state, version);  // said once every check has passed
  if (!a.sky.empty()) state.sky = volume::load_sky_file(a.sky);
  if (!a.files.empty()) {
    // Fog volumes from any tool, where their files put them; no wind (a simulation moves itself).
    state.sky.clouds.clear();
    for (const std::string& f : a.files) {
      volume::SkyCloud c;
      c.file = f;
      c.grid = a.grid;
      c.up = a.up;
      state.sky.clouds.push_back(c);
    }
    state.sky.wind_m_s = glm::dvec3(0.0);
    state.speed = 1.0;  // a sequence plays at its own fps
    volume::validate(state.sky);
  }
  if (!a.scene.empty()) {
    state.scene = a.scene;
    try {
      render::validate(state);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--scene: ") + e.what());
    }
  }
  if (!a.presets.empty()) {
    // The presets side by side, 2.5 km apart west to east, under the default sky's wind and sun.
    state.sky.clouds.clear();
    for (std::size_t i = 0; i < a.presets.size(); ++i) {
      volume::SkyCloud c;
      c.preset = a.presets[i];
      c.seed = static_cast<uint32_t>(i + 1);
      c.position_m = glm::dvec3(2500.0 * (static_cast<double>(i) - 0.5 * (a.presets.size() - 1)), 0.0, 0.0);
      state.sky.clouds.push_back(c);
    }
    volume::validate(state.sky);
  }
  viewer::Script script;
  if (!a.script.empty()) script = viewer::load_script(a.script);
  // Every file the run may write, before any work: none of them an input or each other, each a
  // regular file (or none yet) in a folder that takes it. --state-out may be --state (Ctrl+S
  // saves there by default), but not another input.
  RunInputs inputs;
  inputs.file("--sky", a.sky).file("--script", a.script);
  // Ctrl+S may rewrite --state (it saves there unless --state-out is given); nothing else may.
  if (!a.state.empty() && (a.state_out.empty() || file_identity(a.state) != file_identity(a.state_out)))
    inputs.file("--state", a.state);
  // The files the sky names (its file clouds, every frame of a sequence, and coverage maps),
  // wherever the sky came from.
  inputs.sky(state.sky, !a.sky.empty()     ? "--sky '" + a.sky + "'"
                        : !a.files.empty() ? std::string("FILE")
                        : !a.state.empty() ? "--state '" + a.state + "' sky"
                                           : std::string("the default sky"));
  std::vector<PathArg> writes{{"--state-out", a.state_out}};
  if (!script.record.empty()) writes.push_back({"script record", script.record});
  // Several save_sky events may name one file, written in turn: it is one output (however it is
  // spelled), but no other output may be it.
  std::set<std::string> saved_skies;
  for (const viewer::ScriptEvent& e : script.events)
    if (e.kind == viewer::ScriptEvent::Kind::SaveSky && saved_skies.insert(file_identity(e.path)).second)
      writes.push_back({"script save_sky", e.path});
  check_outputs(writes, inputs);
  // Screenshots (F12, a script's screenshot_every) go to a folder: one that exists or can be made.
  {
    std::error_code ec;
    const auto st = std::filesystem::status(a.screenshot_dir, ec);
    if (std::filesystem::exists(st) && !std::filesystem::is_directory(st))
      throw UsageError("--screenshot-dir '" + echo(a.screenshot_dir) + "': is not a folder");
    check_output_path(std::filesystem::path(a.screenshot_dir) / (".nimbus-probe-" + std::to_string(::getpid())),
                      "--screenshot-dir");
  }
  render::check_sky_cloud_files(state.sky);  // the files a sky or --state names, and the FILE arguments
  if (!version_note.empty()) std::cerr << "note: " << version_note << "\n";
  checks_done();
  viewer::ViewerOptions options;
  options.screenshot_dir = a.screenshot_dir;
  options.shader_dir = a.shader_dir.empty() ? source_shader_dir() : a.shader_dir;
  options.state_path = a.state_out.empty() ? (a.state.empty() ? "nimbus-view.json" : a.state) : a.state_out;
  options.wait_for_keyframes = !a.script.empty();
  options.frame_on_start = !a.files.empty() || !a.presets.empty();
  // A window refines a still view; a script's frames are plain unless it asks for samples.
  options.progressive_samples = a.script.empty() ? static_cast<unsigned>(a.samples) : static_cast<unsigned>(script.samples);
  // A window accumulates moving frames; a script's frames are plain unless it asks.
  options.temporal = a.script.empty() ? !a.no_temporal : script.temporal;

  std::unique_ptr<render::GlContext> headless;
  std::unique_ptr<viewer::Window> window;
  if (a.headless) {
    headless = render::GlContext::create_headless();  // GlUnavailable: one line, exit 1
  } else {
    window = std::make_unique<viewer::Window>(a.script.empty() ? width : script.width,
                                              a.script.empty() ? height : script.height, "nimbus view");
  }
  viewer::Viewer v(state, options);
  v.adaptive().enabled = !a.no_adaptive;
  v.adaptive().budget_ms = a.budget_ms;
  if (!a.script.empty()) {
    const int rc = viewer::run_script(script, v, [&] {
      if (window) viewer::present_in_window(*window, v);
    });
    if (!a.state_out.empty()) {
      v.save_state();
      if (v.failures() > 0 && rc == 0) {
        std::fprintf(stderr, "nimbus view: --state-out: %s\n", echo(v.message(), 1000).c_str());
        return 1;
      }
    }
    return rc;
  }
  return viewer::run_interactive(*window, v);
}

}  // namespace

void add_view_command(CLI::App& app, Action& action) {
  auto a = std::make_shared<ViewArgs>();
  CLI::App* cmd = app.add_subcommand("view", "The interactive animated sky: a window with a panel (docs/viewer.md)");
  cmd->add_option("files", a->files, "Fog volumes (VDB) to show, or sequences name.%04d.vdb played at their fps");
  cmd->add_option("--grid", a->grid, "The files' float grid (default: density, else the first)");
  cmd->add_option("--up-axis", a->up, "The files' up axis: auto (their metadata, else y), y or z (sky files, states and scripts are Z up)")->capture_default_str();
  cmd->add_option("--scene", a->scene, "Under the clouds: sky (default), another scene preset, or none");
  cmd->add_option("--preset", a->presets, "Clouds from these presets, side by side (instead of the default sky)");
  cmd->add_option("--sky", a->sky, "A sky file (JSON: presets, positions, seeds, wind, sun)");
  cmd->add_option("--state", a->state, "Start from this view state (JSON, as Ctrl+S saves it); Ctrl+S/O use it too");
  cmd->add_option("--state-out", a->state_out, "Ctrl+S saves here (and a script saves its last state here)");
  cmd->add_option("--script", a->script, "Run this script (JSON: steps, camera keys, events, screenshots) and exit");
  cmd->add_flag("--headless", a->headless, "With --script: no window (EGL), the same frames");
  cmd->add_option("--size", a->size, "Window size WxH (scripts: the script's size)")->capture_default_str();
  cmd->add_option("--screenshot-dir", a->screenshot_dir, "Where F12 and scripts write nimbus-NNNN.exr/.png")
      ->capture_default_str();
  cmd->add_option("--shader-dir", a->shader_dir, "F5 reloads shaders from here (default: the source tree's, if present)");
  cmd->add_option("--budget-ms", a->budget_ms, "Adaptive quality: frame budget while moving, ms")->capture_default_str();
  cmd->add_flag("--no-adaptive", a->no_adaptive, "Always draw at full quality");
  cmd->add_flag("--no-temporal", a->no_temporal,
                "While the view or the clock moves, show each frame alone, scaled up, instead of accumulated with the "
                "last ones, reprojected (scripts: their \"temporal\" key)");
  cmd->add_option("--samples", a->samples,
                  "A still view is drawn again with sub-pixel and jitter offsets, up to this many times, and the mean "
                  "shown (the slicer's grain goes); 1: one plain frame (scripts: their \"samples\" key)")
      ->capture_default_str();
  cmd->callback([&action, a] { action = [a] { return run_view(*a); }; });
}

}  // namespace nimbus::cli
