// The interactive sky viewer's model: a view state, its clocks, the camera moves, the keys, the
// adaptive quality and the frames, drawn through render::SkyRenderer. No window and no UI here:
// the GLFW window (view_window.cpp) and the scripted runs (view_script.cpp) feed it the same
// events, so a script exercises exactly what a user does.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "adaptive_quality.hpp"
#include "camera_control.hpp"
#include "display.hpp"
#include "nimbus/render/core/image.hpp"
#include "nimbus/render/sky/progressive_frame.hpp"
#include "nimbus/render/sky/temporal_frame.hpp"
#include "nimbus/render/sky/view_state.hpp"
#include "nimbus/render/frame/sky_renderer.hpp"

namespace nimbus::viewer {

enum class Key { Space, Left, Right, G, H, Tab, F5, F12, CtrlS, CtrlO, Escape };

struct ViewerOptions {
  std::string screenshot_dir = ".";         // F12
  std::string state_path = "nimbus-view.json";  // Ctrl+S / Ctrl+O
  std::string shader_dir;                   // F5 reads shaders from here; empty: F5 reports it cannot
  bool wait_for_keyframes = false;          // scripts: every frame is exactly its state
  bool frame_on_start = false;              // after the first frame, frame the clouds (G) and make that home
  // While nothing changes, draw progressive samples and show their mean (progressive_frame.hpp),
  // up to this many; then draw nothing until something changes. 0: every frame is the plain one
  // (scripts, unless they ask: each frame is then exactly `nimbus render --view-state`).
  unsigned progressive_samples = 0;
  // While the camera, the sun or the clock move, draw each frame small (the adaptive quality's
  // level) with a sub-pixel jitter and show it accumulated with the last ones, reprojected
  // (temporal_frame.hpp); the adaptive quality then treats a running clock as motion. false:
  // each frame is the level's frame, scaled up (scripts, unless they ask).
  bool temporal = false;
};

// What the last frame cost and showed.
struct FrameReport {
  render::FrameStats stats;     // GPU passes
  render::SkyFrameInfo info;
  double cpu_ms = 0.0;          // the whole frame on the CPU (render, readback, display)
  bool moving = false;          // the camera or the sun moved for it
  int quality_level = 0;
  unsigned samples = 1;         // progressive samples in the frame shown (1: a plain frame)
  unsigned temporal_frames = 0; // frames accumulated in the temporal frame shown (0: not one)
  double temporal_ms = 0.0;     // CPU time of the accumulation (TemporalFrame::add)
  bool converged = false;       // the still view has all its samples: nothing was drawn
};

class Viewer {
 public:
  // Needs a current GL 4.5 context. Throws std::invalid_argument for a bad state.
  Viewer(render::ViewState state, ViewerOptions options);

  render::ViewState& state() { return state_; }
  const render::ViewState& state() const { return state_; }
  AdaptiveQuality& adaptive() { return adaptive_; }
  // Whether moving frames are accumulated (ViewerOptions::temporal); the panel switches it.
  bool temporal() const { return options_.temporal; }
  void set_temporal(bool on);
  bool fly_mode() const { return fly_; }
  bool quit_requested() const { return quit_; }
  // How many saves, loads and screenshots have failed so far (each also sets message()): a
  // scripted run that had any exits 1.
  int failures() const { return failures_; }
  // The last message for the user (a saved file, an error); shader_error(): the last failed reload.
  const std::string& message() const { return message_; }
  const std::string& shader_error() const { return shader_error_; }

  // Input.
  void key(Key k);
  void drag(int button, double dx_px, double dy_px);  // button 0 left, 1 right
  void scroll(double notches);
  void fly_move(const glm::dvec3& move, double dt_s, bool fast);
  // The clocks, by a real time step (nothing while paused). Also called with 0 each frame.
  void advance(double real_dt_s);
  // The sun by hand (panel), the camera by a script: both mark the frame as moving.
  void set_sun(double elevation_deg, double azimuth_deg);
  void set_camera(const glm::dvec3& eye, const glm::dvec3& look_at) { set_pose({eye, look_at}); }
  // Window pixels on the left that the panel covers (0: none, or collapsed); G frames the clouds
  // in the rest of the view.
  void set_covered_left(double width_px) { covered_left_px_ = std::max(0.0, width_px); }

  // A frame at width x height window pixels (the adaptive quality may draw fewer); the image is
  // kept for display() and screenshots. now_s: real time, for the adaptive quality.
  const render::Image& draw(int width, int height, double now_s);
  // The last frame into the bound framebuffer's viewport.
  void display(int width, int height);
  const FrameReport& report() const { return report_; }
  // The still view holds all its progressive samples: draw() draws nothing until something
  // changes (the window may wait for input instead of spinning).
  bool converged() const { return report_.converged; }
  const render::Image& frame() const { return frame_; }

  // F12: a full-quality frame of the current state at width x height into the screenshot folder
  // as nimbus-NNNN.exr (linear, the state in its metadata) and nimbus-NNNN.png; returns the EXR path.
  std::string screenshot(int width, int height);
  // The same for the last frame as drawn (scripts without adaptive quality: it is full quality).
  std::string save_frame();
  // A full-quality frame of the current state (waits for its keyframes); nothing is kept.
  render::Image full_quality_frame(int width, int height) {
    return renderer_->render(state_, width, height, render::FrameQuality{}, true);
  }
  // A frame of the current state at a given quality (the bench's levels); nothing is kept.
  // `depths`: what each pixel shows and how far (to guide the grain filter as draw() does).
  render::Image render_at(int width, int height, const render::FrameQuality& quality,
                          render::PixelDepths* depths = nullptr) {
    return renderer_->render(state_, width, height, quality, true, nullptr, nullptr, depths);
  }
  render::SkyKeyframes& keyframes() { return renderer_->keyframes(); }
  // The keyframes' light volumes (null until the light-volume method was first drawn).
  const render::KeyframeLightVolumes* light_volumes() const { return renderer_->light_volumes(); }
  // F5: shaders from options.shader_dir; a broken one keeps the running programs (shader_error()).
  void reload_shaders();
  void save_state();
  void load_state();
  // The current sky (clouds, wind, sun) as a sky file, for --sky or another state.
  void save_sky(const std::string& path);

 private:
  CameraPose pose() const { return {state_.camera.eye, state_.camera.look_at}; }
  // Every camera move lands here: over a scene with ground, the eye stays kEyeOverGround_m above it.
  void set_pose(const CameraPose& p);
  static constexpr double kEyeOverGround_m = 2.0;  // as G's framing keeps the eye on the ground
  std::optional<double> lowest_eye_y() const;     // render y; none without ground
  std::string write_shot(render::Image shot);

  render::ViewState state_;
  ViewerOptions options_;
  double covered_left_px_ = 0.0;
  std::unique_ptr<render::SkyRenderer> renderer_;
  std::unique_ptr<Display> display_;
  AdaptiveQuality adaptive_;
  render::ViewState home_;
  // The frame's progressive key: the state and size it shows, so a change starts a new mean.
  std::string progressive_key(int width, int height) const;
  // Whether the progressive mean holds samples of the current state at this size.
  bool mean_is_of(int width, int height) const;
  render::Image frame_;
  render::ProgressiveFrame progressive_;
  // The temporal frame (options_.temporal): its history, the next frame's jitter index, the
  // clouds' drift and the multiple scattering of the last frame it took; reset_temporal_: the
  // next frame starts it again (a new sun, state or programs).
  render::TemporalFrame temporal_;
  unsigned temporal_index_ = 1;
  glm::dvec3 temporal_offset_m_{0.0};
  std::string temporal_multiple_;
  bool reset_temporal_ = false;
  // Draws this frame through the temporal frame; returns the frame shown.
  render::Image draw_temporal(int width, int height, render::FrameQuality quality, FrameReport& r);
  // Draws a plain frame, or a still view's next progressive sample; returns the frame shown
  // (the samples' mean).
  render::Image draw_plain(int width, int height, render::FrameQuality quality, bool still, const std::string& view_key,
                           FrameReport& r);
  FrameReport report_;
  bool fly_ = false, quit_ = false, moved_ = false, framed_ = false;
  bool light_settling_ = false;  // the last frame's light volume was not the full one (a preview, stale, the octaves)
  int last_width_ = 0, last_height_ = 0;
  int failures_ = 0;
  std::string message_, shader_error_;
};

}  // namespace nimbus::viewer
