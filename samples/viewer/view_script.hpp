// Scripted viewer runs (`nimbus view --script FILE.json`): the viewer's own loop and code with no
// input: a fixed time step, camera keyframes, key and mouse events at given frames, and frames
// saved as screenshots every K frames; then it exits. The same script gives the same images in a
// window (Xvfb) or headless (EGL). docs/viewer.md documents the keys.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "viewer.hpp"

namespace nimbus::viewer {

struct ScriptCameraKey {
  int frame = 0;
  glm::dvec3 eye{0.0}, look_at{0.0};  // the renderer's frame; the file holds them Z-up ("version": 2)
};

struct ScriptEvent {
  int frame = 0;
  enum class Kind { Key, Drag, Scroll, Sun, SaveSky } kind = Kind::Key;
  Key key = Key::Space;
  int button = 0;                 // Drag: 0 left, 1 right
  glm::dvec2 amount{0.0};         // Drag: pixels; Scroll: notches in x; Sun: elevation, azimuth degrees
  std::string path;               // SaveSky: the sky file to write
};

struct Script {
  int width = 320, height = 180;  // pixels
  int frames = 10;                // [1, 100000]
  double dt_s = 0.1;              // real seconds per frame, [0, 60]
  int screenshot_every = 0;       // 0: none; else frames 0, K, 2K, ...
  bool adaptive = false;          // on: the adaptive quality runs (on measured frame times, against the script's clock)
  int samples = 0;                // a still view's progressive samples (ViewerOptions); 0: plain frames
  bool temporal = false;          // moving frames through the temporal frame (ViewerOptions)
  std::string record;             // a JSON file of every frame's clocks, keyframes and costs; empty: none
  std::vector<ScriptCameraKey> camera;
  std::vector<ScriptEvent> events;
};

// Throws std::runtime_error naming the file when unreadable or not JSON, std::invalid_argument
// naming the key for bad contents (an event past the last frame among them). The files it
// writes (record, save_sky) are checked by the caller, which knows the run's other files.
Script load_script(const std::string& path);

// Runs the script on `viewer` (built by the caller, with wait_for_keyframes on). present(frame)
// shows each frame (the window's display and swap; nothing headless). Returns 0, or 1 when a
// screenshot, a save, a load or the record failed.
int run_script(const Script& script, Viewer& viewer, const std::function<void()>& present);

}  // namespace nimbus::viewer
