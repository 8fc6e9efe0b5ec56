// The viewer's window, input and loop (view_window.hpp).
#include "view_window.hpp"

#include <epoxy/gl.h>

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "nimbus/render/gl/context.hpp"

namespace nimbus::viewer {
namespace {

// Mouse state between callbacks: the viewer sees drags as pixel deltas.
struct Input {
  Viewer* viewer = nullptr;
  bool dragging[2] = {false, false};
  double x = 0, y = 0;
};

Input& input() {
  static Input in;
  return in;
}

bool gui_has_mouse() { return ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse; }
bool gui_has_keyboard() { return ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard; }

void on_key(GLFWwindow*, int key, int, int action, int mods) {
  Viewer* v = input().viewer;
  if (!v || action != GLFW_PRESS || gui_has_keyboard()) return;
  const bool ctrl = (mods & GLFW_MOD_CONTROL) != 0;
  switch (key) {
    case GLFW_KEY_SPACE: v->key(Key::Space); break;
    case GLFW_KEY_LEFT: v->key(Key::Left); break;
    case GLFW_KEY_RIGHT: v->key(Key::Right); break;
    case GLFW_KEY_G: v->key(Key::G); break;
    case GLFW_KEY_H: v->key(Key::H); break;
    case GLFW_KEY_TAB: v->key(Key::Tab); break;
    case GLFW_KEY_F5: v->key(Key::F5); break;
    case GLFW_KEY_F12: v->key(Key::F12); break;
    case GLFW_KEY_S: if (ctrl) v->key(Key::CtrlS); break;
    case GLFW_KEY_O: if (ctrl) v->key(Key::CtrlO); break;
    case GLFW_KEY_ESCAPE: v->key(Key::Escape); break;
    default: break;
  }
}

void on_button(GLFWwindow*, int button, int action, int) {
  Input& in = input();
  if (button != GLFW_MOUSE_BUTTON_LEFT && button != GLFW_MOUSE_BUTTON_RIGHT) return;
  const int b = button == GLFW_MOUSE_BUTTON_LEFT ? 0 : 1;
  if (action == GLFW_PRESS && !gui_has_mouse()) {
    // The drag starts where the last motion event put the cursor: querying the pointer now
    // would see where it is after every queued event, and lose the drag.
    in.dragging[b] = true;
  } else if (action == GLFW_RELEASE) {
    in.dragging[b] = false;
  }
}

void on_cursor(GLFWwindow*, double x, double y) {
  Input& in = input();
  const double dx = x - in.x, dy = y - in.y;
  in.x = x;
  in.y = y;
  if (!in.viewer) return;
  for (int b = 0; b < 2; ++b) {
    if (in.dragging[b]) in.viewer->drag(b, dx, dy);
  }
}

void on_scroll(GLFWwindow*, double, double dy) {
  if (input().viewer && !gui_has_mouse()) input().viewer->scroll(dy);
}

}  // namespace

Window::Window(int width, int height, const std::string& title) {
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!display || !*display) && (!wayland || !*wayland))
    throw render::GlUnavailable("no display: DISPLAY is not set (run under X or Xvfb, or use --script with --headless)");
  if (!glfwInit()) throw render::GlUnavailable("no display: GLFW cannot open the display '" + std::string(display ? display : "") + "'");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    throw render::GlUnavailable("no OpenGL 4.5 core context: the display offers none (GLFW could not create the window)");
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(0);  // frames as fast as they come; the panel shows their cost
}

Window::~Window() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

void Window::framebuffer_size(int& width, int& height) const { glfwGetFramebufferSize(window_, &width, &height); }
void Window::swap() { glfwSwapBuffers(window_); }
bool Window::should_close() const { return glfwWindowShouldClose(window_); }

void present_in_window(Window& window, Viewer& viewer) {
  int w = 0, h = 0;
  window.framebuffer_size(w, h);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  viewer.display(w, h);
  window.swap();
  glfwPollEvents();
}

int run_interactive(Window& window, Viewer& viewer) {
  GLFWwindow* w = window.handle();
  input().viewer = &viewer;
  // Ours first: ImGui chains to the callbacks installed before it.
  glfwSetKeyCallback(w, on_key);
  glfwSetMouseButtonCallback(w, on_button);
  glfwSetCursorPosCallback(w, on_cursor);
  glfwSetScrollCallback(w, on_scroll);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the user's folder
  PanelState panel;
  {  // the time of day of the state's sun, not a fixed hour
    const app::SunTime t = app::nearest_sun_time({viewer.state().sky.sun_elevation_deg, viewer.state().sky.sun_azimuth_deg},
                                                 panel.latitude_deg, panel.day_of_year);
    panel.hour = t.hour;
    panel.off_path_deg = t.off_path_deg;
  }
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(w, true);
  ImGui_ImplOpenGL3_Init("#version 450 core");
  const auto start = std::chrono::steady_clock::now();
  double last = 0.0;
  while (!window.should_close() && !viewer.quit_requested()) {
    glfwPollEvents();
    const double now = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double dt = now - last;
    last = now;
    if (viewer.fly_mode() && !gui_has_keyboard()) {
      auto down = [&](int k) { return glfwGetKey(w, k) == GLFW_PRESS ? 1.0 : 0.0; };
      const glm::dvec3 move(down(GLFW_KEY_D) - down(GLFW_KEY_A), down(GLFW_KEY_E) - down(GLFW_KEY_Q),
                            down(GLFW_KEY_W) - down(GLFW_KEY_S));
      viewer.fly_move(move, dt, glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS);
    }
    viewer.advance(dt);
    int fw = 0, fh = 0;
    window.framebuffer_size(fw, fh);
    if (fw > 0 && fh > 0) {
      try {
        viewer.draw(fw, fh, now);
      } catch (const std::exception& e) {
        // A frame that cannot be drawn (a keyframe that failed, a bad edit) is reported; the
        // last good frame stays on screen.
        std::fprintf(stderr, "nimbus view: %s\n", e.what());
        if (std::string(e.what()).find("sky keyframe") != std::string::npos) throw;
      }
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
      viewer.display(fw, fh);
    }
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    draw_panel(viewer, panel);
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    window.swap();
    // A converged still view draws nothing new: wait for input rather than spin.
    if (viewer.converged()) glfwWaitEventsTimeout(0.1);
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  input().viewer = nullptr;
  return 0;
}

}  // namespace nimbus::viewer
