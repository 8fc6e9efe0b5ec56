// The sky viewer's model (viewer.hpp).
#include "viewer.hpp"

#include "nimbus/base/staged_files.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "nimbus/render/core/cloud_framing.hpp"
#include "nimbus/render/gl/shader_program.hpp"
#include "nimbus/render/gl/shader_source.hpp"
#include "nimbus/render/image/image_io.hpp"
#include "nimbus/volume/sky.hpp"

namespace nimbus::viewer {
namespace {

// Whether a frame showed the state as it will stay: its keyframes were there and its light
// volume is the full one (not a preview, a stale one, or the octaves standing in).
bool final_frame(const render::SkyFrameInfo& info, const render::ViewState& state) {
  if (info.waited) return false;
  return state.slices.multiple.method != render::MultipleScatteringMethod::LightVolume || info.multiple == "light volume";
}

}  // namespace

Viewer::Viewer(render::ViewState state, ViewerOptions options)
    : state_(std::move(state)), options_(std::move(options)), home_(state_) {
  render::validate(state_);
  adaptive_.temporal = options_.temporal;
  renderer_ = std::make_unique<render::SkyRenderer>(state_);
  display_ = std::make_unique<Display>();
}

std::optional<double> Viewer::lowest_eye_y() const {
  const std::optional<render::Scene>& scene = renderer_->scene();  // the one drawn: no second copy
  if (!scene || !scene->ground) return std::nullopt;
  return scene->ground->height_m + kEyeOverGround_m;
}

void Viewer::set_pose(const CameraPose& moved) {
  // Over a scene with ground, no move takes the eye under it (camera_control.hpp).
  const std::optional<double> lowest = lowest_eye_y();
  const CameraPose p = lowest ? keep_eye_above(moved, *lowest) : moved;
  if (p.eye == state_.camera.eye && p.look_at == state_.camera.look_at) return;
  state_.camera.eye = p.eye;
  state_.camera.look_at = p.look_at;
  moved_ = true;
}

void Viewer::key(Key k) {
  switch (k) {
    case Key::Space:
      state_.paused = !state_.paused;
      message_ = state_.paused ? "paused" : "running";
      break;
    case Key::Left:
    case Key::Right:
      if (state_.paused) {
        // Half a second of sky time at speed 1, scaled with the speed (at least half a second).
        const double step = (k == Key::Right ? 0.5 : -0.5) * std::max(1.0, state_.speed);
        state_.sky_time_s += step;
        state_.evolution_time_s += step;
      }
      break;
    case Key::G: {
      const auto& clouds = renderer_->clouds();
      if (clouds.empty()) break;
      const int width = std::max(last_width_, 16), height = std::max(last_height_, 16);
      render::Camera c = render::state_camera(state_, width, height, clouds);
      // Over the sky scene's ground the eye stays on it (2 m up), looking up at the clouds.
      const render::Camera f = render::frame_clouds_right_of(c, clouds, state_.scene == "sky", covered_left_px_);
      set_pose({f.eye, f.look_at});
      break;
    }
    case Key::H:
      set_pose({home_.camera.eye, home_.camera.look_at});
      break;
    case Key::Tab:
      fly_ = !fly_;
      message_ = fly_ ? "fly: WASD, Q/E down/up, Shift fast, left drag looks" : "orbit";
      break;
    case Key::F5:
      reload_shaders();
      break;
    case Key::F12:
      try {
        message_ = "saved " + screenshot(std::max(last_width_, 16), std::max(last_height_, 16));
      } catch (const std::exception& e) {
        message_ = std::string("screenshot failed: ") + e.what();
        ++failures_;
      }
      break;
    case Key::CtrlS:
      save_state();
      break;
    case Key::CtrlO:
      load_state();
      break;
    case Key::Escape:
      quit_ = true;
      break;
  }
}

void Viewer::drag(int button, double dx, double dy) {
  if (button == 0) {
    set_pose(fly_ ? fly_look(pose(), dx, dy) : tumble(pose(), dx, dy));
  } else if (button == 1) {
    set_pose(pan(pose(), dx, dy, state_.camera.fov_deg, std::max(last_width_, 1)));
  }
}

void Viewer::scroll(double notches) {
  if (notches != 0.0) set_pose(zoom(pose(), notches));
}

void Viewer::fly_move(const glm::dvec3& move, double dt_s, bool fast) {
  if (move == glm::dvec3(0.0) || dt_s <= 0.0) return;
  // 150 m/s (750 with Shift): a cloud a kilometre across passes in seconds.
  set_pose(viewer::fly_move(pose(), move, fast ? 750.0 : 150.0, dt_s));
}

void Viewer::advance(double real_dt_s) {
  if (state_.paused || !(real_dt_s > 0.0)) return;
  const double dt = state_.speed * real_dt_s;
  state_.sky_time_s += dt;
  state_.evolution_time_s += dt;
}

void Viewer::set_sun(double elevation_deg, double azimuth_deg) {
  if (elevation_deg == state_.sky.sun_elevation_deg && azimuth_deg == state_.sky.sun_azimuth_deg) return;
  state_.sky.sun_elevation_deg = elevation_deg;
  state_.sky.sun_azimuth_deg = azimuth_deg;
  moved_ = true;
  reset_temporal_ = true;  // another light on everything: nothing of the last frames carries over
}

std::string Viewer::progressive_key(int width, int height) const {
  return render::view_state_to_json(state_).dump() + " " + std::to_string(width) + "x" + std::to_string(height);
}

bool Viewer::mean_is_of(int width, int height) const {
  return progressive_.samples() > 0 && progressive_.key().starts_with(progressive_key(width, height) + " |");
}

const render::Image& Viewer::draw(int width, int height, double now_s) {
  last_width_ = width;
  last_height_ = height;
  // A still view (nothing moved, full quality, the same state and size as the mean's) draws
  // its next progressive sample; a changed one starts again from the plain frame.
  const std::string view_key = progressive_key(width, height);
  const bool still = options_.progressive_samples > 0 && !moved_ && adaptive_.level() == 0 && mean_is_of(width, height);
  if (still && report_.converged) return frame_;
  if (still && progressive_.samples() >= options_.progressive_samples && final_frame(report_.info, state_)) {
    report_.converged = true;
    return frame_;
  }
  const auto start = std::chrono::steady_clock::now();
  FrameReport r;
  r.quality_level = adaptive_.level();
  r.moving = moved_;
  // With the temporal frame, a running clock is motion too: the frames are drawn small and
  // accumulated, as while the camera moves.
  const bool clock_runs = !state_.paused && state_.speed != 0.0;
  // A light still settling (a new sun's quick volume, an old one's, or the octaves standing in,
  // on screen while the full volume is built) is motion too: a full-quality frame of it would be replaced when the full
  // volume lands, and drawn small the new light shows a frame sooner.
  const bool animating = moved_ || (options_.temporal && clock_runs) || light_settling_;
  render::FrameQuality quality = adaptive_.quality(state_.slices.slices, state_.slices.light_res);
  if (options_.temporal && animating && !still) {
    frame_ = draw_temporal(width, height, quality, r);
  } else {
    temporal_.reset();
    frame_ = draw_plain(width, height, quality, still, view_key, r);
  }
  r.cpu_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  adaptive_.update(animating, r.cpu_ms, now_s);
  moved_ = false;
  light_settling_ = state_.slices.multiple.method == render::MultipleScatteringMethod::LightVolume &&
                    r.info.multiple != "light volume";
  report_ = r;
  if (options_.frame_on_start && !framed_) {
    // Clouds nobody placed a camera for (files, presets): look at them from here on.
    framed_ = true;
    key(Key::G);
    home_.camera.eye = state_.camera.eye;
    home_.camera.look_at = state_.camera.look_at;
  }
  return frame_;
}

render::Image Viewer::draw_plain(int width, int height, render::FrameQuality quality, bool still,
                                 const std::string& view_key, FrameReport& r) {
  quality.sample = render::progressive_sample(still ? progressive_.samples() : 0);
  render::PixelDepths depths;  // to guide the still's grain filter
  render::Image frame =
      renderer_->render(state_, width, height, quality, options_.wait_for_keyframes, &r.stats, &r.info, &depths);
  // The evolution waits while its keyframes are made: carry on from what was drawn.
  if (r.info.waited) state_.evolution_time_s = r.info.evolution_time_s;
  if (options_.progressive_samples == 0 || r.quality_level != 0) {
    progressive_.reset();
    return frame;
  }
  // What was drawn joins the key: a light volume replacing its preview, or keyframes that
  // arrived, start a new mean although the state held still.
  progressive_.add(frame, view_key + " | " + r.info.multiple + " | " + frame.metadata["keyframes"] + " | " +
                              frame.metadata["evolution_time_s"]);
  r.samples = progressive_.samples();
  // The mean of few jittered frames still holds grain: filtered (grain_filter.hpp).
  return render::still_picture(progressive_.mean(), progressive_.samples(), depths, state_.grain_filter, state_.slices.jitter);
}

void Viewer::set_temporal(bool on) {
  options_.temporal = on;
  adaptive_.temporal = on;
  reset_temporal_ = true;
}

render::Image Viewer::draw_temporal(int width, int height, render::FrameQuality quality, FrameReport& r) {
  progressive_.reset();
  quality.sample.pixel_offset = render::temporal_pixel_offset(temporal_index_);
  quality.sample.jitter_frame = temporal_index_;
  ++temporal_index_;
  render::PixelDepths depths;
  render::Image frame =
      renderer_->render(state_, width, height, quality, options_.wait_for_keyframes, &r.stats, &r.info, &depths);
  if (r.info.waited) state_.evolution_time_s = r.info.evolution_time_s;
  // A light volume replacing its preview or a stale one relights everything: start again.
  if (reset_temporal_ || r.info.multiple != temporal_multiple_) temporal_.reset();
  reset_temporal_ = false;
  const glm::dvec3 shift = temporal_.frames() > 0 ? r.info.cloud_offset_m - temporal_offset_m_ : glm::dvec3(0.0);
  temporal_offset_m_ = r.info.cloud_offset_m;
  temporal_multiple_ = r.info.multiple;
  const auto [ow, oh] = render::scaled_frame_size(width, height, std::clamp(state_.render_scale, 0.01, 1.0));
  const auto start = std::chrono::steady_clock::now();
  render::Image shown = temporal_.add(frame, r.info.camera, depths, std::max(ow, frame.width), std::max(oh, frame.height), shift);
  r.temporal_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  r.temporal_frames = temporal_.frames();
  return shown;
}

void Viewer::display(int width, int height) {
  if (frame_.width > 0) display_->draw(frame_, width, height, state_.exposure_stops);
}

std::string Viewer::screenshot(int width, int height) {
  // Full quality and exactly the state, whatever the adaptive quality drew last: the still
  // view's mean where it is of this state and size, else a plain frame.
  if (mean_is_of(width, height) && final_frame(report_.info, state_))
    return write_shot(progressive_.mean());
  return write_shot(renderer_->render(state_, width, height, render::FrameQuality{}, true));
}

std::string Viewer::save_frame() {
  if (frame_.width == 0) throw std::logic_error("no frame drawn yet");
  return write_shot(frame_);
}

std::string Viewer::write_shot(render::Image shot) {
  namespace fs = std::filesystem;
  const fs::path dir(options_.screenshot_dir);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir)) throw std::runtime_error("screenshot folder '" + dir.string() + "' cannot be made");
  int n = 1;
  char name[32];
  for (;; ++n) {
    if (n > 9999) throw std::runtime_error("screenshot folder '" + dir.string() + "' already holds nimbus-0001 to 9999");
    std::snprintf(name, sizeof name, "nimbus-%04d", n);
    // symlink_status: a dangling link or a FIFO of that name is taken, not written through.
    if (!fs::exists(fs::symlink_status(dir / (std::string(name) + ".exr"))) &&
        !fs::exists(fs::symlink_status(dir / (std::string(name) + ".png"))))
      break;
  }
  shot.metadata["screenshot"] = name;
  const fs::path exr = dir / (std::string(name) + ".exr");
  render::PreviewOptions po;
  po.exposure_stops = state_.exposure_stops;
  StagedFiles files;  // both or neither
  files.write(exr, [&](const fs::path& tmp) { render::write_exr(tmp, shot); });
  files.write(dir / (std::string(name) + ".png"), [&](const fs::path& tmp) { render::write_png_preview(tmp, shot, po); });
  files.commit();
  return exr.string();
}

void Viewer::reload_shaders() {
  if (options_.shader_dir.empty()) {
    shader_error_.clear();
    message_ = "F5: no shader folder (run from a source tree, or give --shader-dir)";
    return;
  }
  const std::vector<render::ShaderFile> previous = render::shader_overrides();
  try {
    render::set_shader_overrides(render::read_shader_dir(options_.shader_dir));
    // Build everything anew and draw one small frame, which compiles every program this state
    // uses; only then replace the running ones.
    auto renderer = std::make_unique<render::SkyRenderer>(state_, renderer_->shared_keyframes());
    auto display = std::make_unique<Display>();
    renderer->render(state_, 64, 36, render::FrameQuality{}, false);
    renderer_ = std::move(renderer);
    display_ = std::move(display);
    reset_temporal_ = true;
    shader_error_.clear();
    message_ = "shaders reloaded from " + options_.shader_dir;
  } catch (const std::exception& e) {
    render::set_shader_overrides(previous);
    shader_error_ = e.what();
    message_ = "shader reload failed; the last good programs keep running";
  }
}

void Viewer::save_state() {
  try {
    render::save_view_state(state_, options_.state_path);
    message_ = "saved " + options_.state_path;
  } catch (const std::exception& e) {
    message_ = std::string("save failed: ") + e.what();
    ++failures_;
  }
}

void Viewer::save_sky(const std::string& path) {
  try {
    volume::save_sky_file(state_.sky, path);
    message_ = "saved the sky as " + path;
  } catch (const std::exception& e) {
    message_ = std::string("saving the sky failed: ") + e.what();
    ++failures_;
  }
}

void Viewer::load_state() {
  try {
    int version = render::kViewStateVersion;
    state_ = render::load_view_state(options_.state_path, &version);
    moved_ = true;
    reset_temporal_ = true;
    const std::string note = render::view_state_version_note(options_.state_path, version);
    message_ = note.empty() ? "loaded " + options_.state_path : note;
  } catch (const std::exception& e) {
    message_ = std::string("load failed: ") + e.what();
    ++failures_;
  }
}

}  // namespace nimbus::viewer
