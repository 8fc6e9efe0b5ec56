// Camera and image-size flags shared by the rendering commands (render_args.hpp).
#include "render_args.hpp"

#include <cmath>
#include <mutex>
#include <regex>
#include <sstream>

#include "nimbus/base/validate.hpp"
#include "nimbus/render/core/world_axes.hpp"
#include "nimbus/render/reference/reference_renderer.hpp"
#include "progress.hpp"
#include "setting_flags.hpp"

namespace nimbus::cli {

glm::dvec3 parse_vec3(const std::string& flag, const std::string& text) {
  static const std::regex re(R"(\s*([^,\s]+)\s*,\s*([^,\s]+)\s*,\s*([^,\s]+)\s*)");
  std::smatch m;
  if (!std::regex_match(text, m, re)) throw UsageError(flag + ": '" + text + "' must be three numbers X,Y,Z");
  glm::dvec3 v;
  for (int i = 0; i < 3; ++i) {
    std::size_t used = 0;
    double x = 0;
    try {
      x = std::stod(m[i + 1].str(), &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != static_cast<std::size_t>(m[i + 1].length()) || !std::isfinite(x))
      throw UsageError(flag + ": '" + text + "' must be three finite numbers X,Y,Z");
    if (std::abs(x) > kMaxFlagMagnitude)
      throw UsageError(flag + ": '" + text + "' must be three numbers within +-1e12");
    v[i] = x;
  }
  return v;
}

glm::dvec3 parse_world_vec3(const std::string& flag, const std::string& text) {
  return render::world_to_render(parse_vec3(flag, text));
}

void check_exposure(const std::optional<double>& stops) {
  check_flag(render::Setting::Exposure, stops);
}

std::pair<int, int> parse_resolution(const std::string& flag, const std::string& text) {
  std::smatch m;
  if (!std::regex_match(text, m, std::regex(R"((\d{1,6})x(\d{1,6}))")))
    throw UsageError(flag + ": '" + text + "' must be WIDTHxHEIGHT, e.g. 1280x720");
  const int w = std::stoi(m[1].str()), h = std::stoi(m[2].str());
  if (w < 1 || h < 1 || w > 16384 || h > 16384)
    throw UsageError(flag + ": '" + text + "' width and height must be in [1, 16384]");
  return {w, h};
}

std::vector<std::pair<int, int>> parse_resolutions(const std::string& flag, const std::string& list) {
  std::vector<std::pair<int, int>> sizes;
  std::stringstream ss(list);
  for (std::string item; std::getline(ss, item, ',');) sizes.push_back(parse_resolution(flag, item));
  if (sizes.empty()) throw UsageError(flag + ": give at least one WxH");
  return sizes;
}

void add_camera_options(CLI::App* cmd, CameraArgs& a) {
  cmd->add_option("--eye", a.eye, "Camera position X,Y,Z, metres (Z up: x east, y north)");
  cmd->add_option("--look-at", a.look_at, "Point the camera looks at, X,Y,Z, metres (Z up: x east, y north)");
  cmd->add_option("--up", a.up, "Camera up vector X,Y,Z (Z up; default 0,0,1)");
  add_setting_option(cmd, render::Setting::Fov, a.fov_deg);
  cmd->add_option("--res", a.res, "Image size WIDTHxHEIGHT");
}

void check_camera_flags(const CameraArgs& a) {
  if (!a.eye.empty()) parse_world_vec3("--eye", a.eye);
  if (!a.look_at.empty()) parse_world_vec3("--look-at", a.look_at);
  if (!a.up.empty()) parse_world_vec3("--up", a.up);
  check_flag(render::Setting::Fov, a.fov_deg);
  if (!a.res.empty()) parse_resolution("--res", a.res);
}

render::Camera apply_camera_args(const CameraArgs& a, render::Camera c) {
  if (!a.eye.empty()) c.eye = parse_world_vec3("--eye", a.eye);
  if (!a.look_at.empty()) c.look_at = parse_world_vec3("--look-at", a.look_at);
  if (!a.up.empty()) c.up = parse_world_vec3("--up", a.up);
  if (a.fov_deg) {
    check_flag(render::Setting::Fov, *a.fov_deg);
    c.fov_deg = *a.fov_deg;
  }
  if (!a.res.empty()) std::tie(c.width, c.height) = parse_resolution("--res", a.res);
  try {
    render::validate(c);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("camera flags: ") + e.what());
  }
  return c;
}

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

render::Image render_reference_with_progress(const render::Scene& scene, const render::Camera& camera, bool surface_airlight) {
  Progress progress("reference " + scene.name);
  std::mutex m;
  render::ReferenceSettings rs;
  rs.surface_airlight = surface_airlight;
  rs.progress = [&](double f) {
    std::lock_guard<std::mutex> lock(m);
    progress.update(f);
  };
  return render::render_reference(scene, camera, rs);
}

}  // namespace nimbus::cli
