// The viewer's desktop window: GLFW 3.3 with an OpenGL 4.5 core context, the Dear ImGui panel
// (view_panel.cpp), and the mapping of keys and mouse to the viewer's events.
#pragma once
#include <memory>
#include <string>

#include "nimbus/app/sun_path.hpp"
#include "nimbus/volume/sky.hpp"
#include "viewer.hpp"

struct GLFWwindow;

namespace nimbus::viewer {

// A window with a current GL 4.5 core context. Throws render::GlUnavailable with one line
// naming what is missing (no display, no GL 4.5 core).
class Window {
 public:
  Window(int width, int height, const std::string& title);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;
  GLFWwindow* handle() const { return window_; }
  void framebuffer_size(int& width, int& height) const;
  void swap();
  bool should_close() const;

 private:
  GLFWwindow* window_ = nullptr;
};

// Interactive: events, frames and the panel until Escape or the window closes. Returns 0.
int run_interactive(Window& window, Viewer& viewer);

// Shows a scripted frame in the window (display and swap, events polled so it stays responsive).
void present_in_window(Window& window, Viewer& viewer);

// What the panel remembers between frames, beside the viewer's state: the time-of-day slider and
// a cloud edit in progress (applied when its control is released).
struct PanelState {
  double hour = 15.0;  // the time-of-day control (app/sun_path.hpp), local solar time
  double latitude_deg = app::kDefaultLatitudeDeg;
  double day_of_year = app::kDefaultDayOfYear;
  double off_path_deg = 0.0;  // how far the sun set by elevation and azimuth is from the day's path
  volume::Sky edit;
  bool editing = false;
};

// The panel (view_panel.cpp): clouds, sun, optics, renderer, frame times. Between ImGui::NewFrame
// and ImGui::Render.
void draw_panel(Viewer& viewer, PanelState& panel);

}  // namespace nimbus::viewer
