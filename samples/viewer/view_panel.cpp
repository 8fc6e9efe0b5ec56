// The viewer's panel (view_window.hpp): what the common cloud demos offer (sun, wind, coverage,
// density, optics, steps, an ms/fps line), plus per-pass times and the adaptive quality's choice.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "nimbus/app/sun_path.hpp"
#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/volume/preset.hpp"
#include "view_window.hpp"

namespace nimbus::viewer {
namespace {

constexpr double kPi = 3.14159265358979323846;

bool slider(const char* label, double& v, double lo, double hi, const char* fmt = "%.3f", bool log = false) {
  float f = static_cast<float>(v);
  const bool changed = ImGui::SliderFloat(label, &f, static_cast<float>(lo), static_cast<float>(hi), fmt,
                                          log ? ImGuiSliderFlags_Logarithmic : 0);
  if (changed) v = f;
  return changed;
}

// The last item's longer explanation, on hover.
void tip(const char* text) {
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
}

// One line of text that never wraps (the panel's layout does not move when it changes); the whole
// text on hover when it is clipped.
void one_line(const std::string& text, const ImVec4* colour = nullptr) {
  const std::string shown = text.empty() ? " " : text;
  if (colour) ImGui::PushStyleColor(ImGuiCol_Text, *colour);
  ImGui::TextUnformatted(shown.c_str());
  if (colour) ImGui::PopStyleColor();
  if (!text.empty()) tip(text.c_str());
}

// A preset's description up to its first full stop: the one line under its drop-down.
std::string first_sentence(const std::string& text) {
  const std::size_t stop = text.find(". ");
  return stop == std::string::npos ? text : text.substr(0, stop + 1);
}

// Panel defaults: a quarter of the window's width, see-through, most sections closed.
constexpr float kPanelShare = 0.25f;
constexpr float kMinSliderWidth = 90.0f;        // pixels
constexpr const char* kLongestLabel = "forward weight";  // the sliders' longest label
constexpr float kPanelAlpha = 0.6f;

// A shader that failed to reload: its error in a window of its own at the bottom, so the panel does not move.
void shader_error_window(const std::string& error) {
  if (error.empty()) return;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y - 8.0f), ImGuiCond_Always, ImVec2(0.5f, 1.0f));
  ImGui::SetNextWindowSize(ImVec2(display.x * 0.6f, 0.0f), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.8f);
  ImGui::Begin("shader error (F5 reloads; the last good program runs)", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoSavedSettings);
  ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "%s", error.c_str());
  ImGui::End();
}

// Two status lines that keep their place whatever they say.
void status_lines(Viewer& viewer, const FrameReport& r) {
  char status[160];
  if (r.temporal_frames > 0)
    std::snprintf(status, sizeof status, "%.1f fps  %.0f ms  %dx%d  %d slices  q%d  %u accumulated", r.cpu_ms > 0 ? 1000.0 / r.cpu_ms : 0.0,
                  r.cpu_ms, r.info.width, r.info.height, r.info.slices, r.quality_level, r.temporal_frames);
  else
    std::snprintf(status, sizeof status, "%.1f fps  %.0f ms  %dx%d  %d slices  q%d  %u sample%s%s", r.cpu_ms > 0 ? 1000.0 / r.cpu_ms : 0.0,
                  r.cpu_ms, r.info.width, r.info.height, r.info.slices, r.quality_level, r.samples, r.samples == 1 ? "" : "s",
                  r.converged ? ", still" : "");
  one_line(status);
  const ImVec4 quiet(0.75f, 0.85f, 1.0f, 1.0f);
  one_line(viewer.message(), &quiet);
}

// The clock: pause, speed, the sky's and the evolution's times.
void time_section(render::ViewState& s, const FrameReport& r) {
  ImGui::Checkbox("paused", &s.paused);
  tip("Space pauses and resumes; Left/Right step while paused");
  slider("speed x", s.speed, 0.0, 1000.0, "%.1f", true);
  tip("sky seconds per real second");
  ImGui::Text("sky %.1f s, evolution %.1f s%s", s.sky_time_s, s.evolution_time_s, r.info.waited ? " (waiting)" : "");
}

// The sun by elevation and azimuth, or by the time of day, latitude and day of the year, kept consistent.
void sun_section(Viewer& viewer, PanelState& panel, render::ViewState& s) {
  double el = s.sky.sun_elevation_deg, az = s.sky.sun_azimuth_deg;
  bool moved = slider("elevation", el, volume::kSunElevationRangeDeg.lo, volume::kSunElevationRangeDeg.hi, "%.1f");
  tip("degrees above the horizon");
  moved |= slider("azimuth", az, volume::kSunAzimuthRangeDeg.lo, volume::kSunAzimuthRangeDeg.hi, "%.1f");
  tip("compass bearing, degrees: 0 north, 90 east");
  bool day_moved = slider("time of day", panel.hour, app::kHourRange.lo, app::kHourRange.hi, "%.2f");
  tip("local solar time, hours; with the latitude and the day of the year it sets the elevation and azimuth");
  day_moved |= slider("latitude", panel.latitude_deg, app::kLatitudeRangeDeg.lo, app::kLatitudeRangeDeg.hi, "%.1f");
  day_moved |= slider("day of year", panel.day_of_year, app::kDayOfYearRange.lo, app::kDayOfYearRange.hi, "%.0f");
  if (day_moved) {
    // The renderer's suns end 10 degrees below the horizon: night holds the sun there.
    const app::SunPosition sun = app::sun_at(panel.hour, panel.latitude_deg, panel.day_of_year);
    el = std::max(sun.elevation_deg, volume::kSunElevationRangeDeg.lo);
    az = sun.azimuth_deg;
    moved = true;
  } else if (moved) {
    // The time of day follows a sun set by its elevation and azimuth: the nearest time on this
    // day's path, and how far off the path that sun is.
    const app::SunTime t = app::nearest_sun_time({el, az}, panel.latitude_deg, panel.day_of_year);
    panel.hour = t.hour;
    panel.off_path_deg = t.off_path_deg;
  }
  if (day_moved) panel.off_path_deg = 0.0;
  if (panel.off_path_deg > 0.5) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
    ImGui::TextWrapped("sun %.0f deg off this day's path", panel.off_path_deg);  // whole at any width
    ImGui::PopStyleColor();
    tip("the elevation and azimuth set a sun this latitude and day never have; the time shown is the nearest one");
  }
  if (moved) viewer.set_sun(el, az);
}

// Each cloud's preset, coverage and density (applied on release: they need new keyframes), evolution and wind.
void clouds_section(PanelState& panel, render::ViewState& s) {
  // Edits that need new keyframes apply when the control is released.
  volume::Sky& edit = panel.edit;
  bool& editing = panel.editing;
  if (!editing) edit = s.sky;
  bool done = false;
  const std::vector<volume::PresetInfo>& presets = volume::list_presets();
  for (std::size_t i = 0; i < edit.clouds.size(); ++i) {
    ImGui::PushID(static_cast<int>(i));
    volume::SkyCloud& c = edit.clouds[i];
    std::string description;
    if (ImGui::BeginCombo("preset", c.preset.empty() ? "(a file)" : c.preset.c_str())) {
      for (const auto& p : presets) {
        if (p.genus == "gas") continue;
        if (ImGui::Selectable(p.name.c_str(), p.name == c.preset)) {
          c.preset = p.name;
          c.overrides = nlohmann::json::object();
          done = true;
        }
        tip(p.description.c_str());
      }
      ImGui::EndCombo();
    }
    for (const auto& p : presets)
      if (p.name == c.preset) description = first_sentence(p.description);
    const ImVec4 grey(0.7f, 0.7f, 0.7f, 1.0f);
    one_line(description, &grey);
    if (c.preset.empty()) {  // a file cloud: nothing of a preset to edit
      ImGui::Separator();
      ImGui::PopID();
      continue;
    }
    const nlohmann::json base = volume::load_preset(c.preset).at("cloud");
    double coverage = c.overrides.value("coverage", base.value("coverage", 0.5));
    double density = c.overrides.value("density", base.value("density", 1.0));
    if (slider("coverage", coverage, 0.05, 1.0)) c.overrides["coverage"] = coverage;
    editing |= ImGui::IsItemActive();
    done |= ImGui::IsItemDeactivatedAfterEdit();
    if (slider("density", density, 0.05, 4.0)) c.overrides["density"] = density;
    editing |= ImGui::IsItemActive();
    done |= ImGui::IsItemDeactivatedAfterEdit();
    ImGui::Separator();
    ImGui::PopID();
  }
  if (slider("evolution x", edit.evolution_scale, 0.0, 50.0, "%.2f")) editing = true;
  tip("multiplies each preset's evolution rate");
  done |= ImGui::IsItemDeactivatedAfterEdit();
  if (done) {
    edit.wind_m_s = s.sky.wind_m_s;
    edit.sun_elevation_deg = s.sky.sun_elevation_deg;
    edit.sun_azimuth_deg = s.sky.sun_azimuth_deg;
    s.sky = edit;
    editing = false;
  }
  // Wind: speed and the compass direction it blows towards; drift needs no new keyframes.
  double speed = std::hypot(s.sky.wind_m_s.x, s.sky.wind_m_s.y);
  double towards = std::fmod(std::atan2(s.sky.wind_m_s.x, s.sky.wind_m_s.y) * 180.0 / kPi + 360.0, 360.0);
  bool wind = slider("wind m/s", speed, 0.0, 60.0, "%.1f");
  wind |= slider("wind to", towards, 0.0, 359.9, "%.0f");
  tip("the compass direction the wind blows towards, degrees");
  if (wind) {
    s.sky.wind_m_s.x = speed * std::sin(towards * kPi / 180.0);
    s.sky.wind_m_s.y = speed * std::cos(towards * kPi / 180.0);
  }
}

// The clouds' optics and multiple scattering.
void optics_section(render::ViewState& s) {
  slider("extinction /m", s.optics.extinction_per_m, 0.001, 0.5, "%.4f", true);
  tip("extinction per metre per unit of density");
  double albedo = s.optics.albedo.x;
  if (slider("albedo", albedo, 0.5, 1.0, "%.3f")) s.optics.albedo = glm::dvec3(albedo);
  render::Phase lobes = render::as_dual_lobes(s.optics.phase);
  bool phase_moved = slider("g forward", lobes.g, 0.0, 0.95);
  phase_moved |= slider("g back", lobes.g_back, -0.95, 0.0);
  phase_moved |= slider("forward weight", lobes.forward_weight, 0.0, 1.0);
  if (phase_moved) s.optics.phase = lobes;
  tip("the dual-lobe phase function: forward and back Henyey-Greenstein lobes and the forward one's weight");
  bool volume = s.slices.multiple.method == render::MultipleScatteringMethod::LightVolume;
  const bool clicked = ImGui::Checkbox("light volume", &volume);
  tip("photon-traced multiple scattering, made per keyframe in the background");
  if (clicked)
    s.slices.multiple.method = volume ? render::MultipleScatteringMethod::LightVolume : render::MultipleScatteringMethod::Octaves;
  if (volume) {
    ImGui::SliderInt("cells", &s.slices.multiple.light_volume.resolution, 16, 96);
    int photons_log2 = static_cast<int>(std::lround(std::log2(static_cast<double>(s.slices.multiple.light_volume.photons))));
    if (ImGui::SliderInt("photons log2", &photons_log2, 14, 24)) s.slices.multiple.light_volume.photons = std::int64_t{1} << photons_log2;
  }
  ImGui::SliderInt("octaves", &s.slices.multiple.octaves, 0, 3);
  tip(volume ? "multiple-scattering octaves, drawn until the light volume is made" : "multiple-scattering octaves");
}

// Slices, light buffer, shafts, scale, exposure, adaptive quality and accumulation.
void renderer_section(Viewer& viewer, render::ViewState& s) {
  ImGui::SliderInt("slices", &s.slices.slices, 8, 512);
  static const int light_sizes[] = {64, 128, 256, 512, 1024};
  if (ImGui::BeginCombo("light buffer", std::to_string(s.slices.light_res).c_str())) {
    for (int n : light_sizes)
      if (ImGui::Selectable(std::to_string(n).c_str(), n == s.slices.light_res)) s.slices.light_res = n;
    ImGui::EndCombo();
  }
  static const char* shafts[] = {"analytic", "raymarch:8", "raymarch:24", "raymarch:48", "shadowvolume"};
  const std::string current = render::to_string(s.shafts);
  if (ImGui::BeginCombo("shafts", current.c_str())) {
    for (const char* m : shafts) {
      const render::ShaftMethod option = render::parse_shaft_method(m);
      if (ImGui::Selectable(m, current == render::to_string(option))) s.shafts = option;
    }
    ImGui::EndCombo();
  }
  slider("render scale", s.render_scale, 0.1, 1.0, "%.2f");
  slider("exposure", s.exposure_stops, -6.0, 6.0, "%.2f");
  tip("stops");
  AdaptiveQuality& a = viewer.adaptive();
  ImGui::Checkbox("adaptive", &a.enabled);
  tip("adaptive quality: fewer slices and pixels while things move, to hold the frame budget");
  bool temporal = viewer.temporal();
  if (ImGui::Checkbox("accumulate", &temporal)) viewer.set_temporal(temporal);
  tip("accumulate moving frames (temporal reprojection)");
  slider("budget ms", a.budget_ms, 10.0, 1000.0, "%.0f", true);
  tip("the adaptive quality's frame budget");
}

// The last frame's times per pass.
void frame_times_section(render::ViewState& s, const FrameReport& r) {
  const render::FrameStats& st = r.stats;
  ImGui::Text("CPU frame      %7.1f ms", r.cpu_ms);
  ImGui::Text("GPU scene      %7.1f ms", st.scene.total_ms);
  ImGui::Text("GPU cloud light%7.1f ms", st.clouds.light_ms);
  ImGui::Text("GPU slices     %7.1f ms", st.clouds.slices_ms);
  ImGui::Text("GPU composite  %7.1f ms", st.clouds.composite_ms);
  ImGui::Text("keyframe upload%7.1f ms", r.info.upload_ms);
  ImGui::Text("multiple scattering: %s", r.info.multiple.c_str());
  if (s.slices.multiple.method == render::MultipleScatteringMethod::LightVolume) ImGui::Text("light volume mix %6.1f ms", r.info.light_volume_ms);
  ImGui::Text("keyframes %lld+1, blend %.2f", static_cast<long long>(r.info.keyframe), r.info.blend);
  ImGui::TextWrapped("%s", st.clouds.timing.c_str());
}

// Frame, home, screenshot, save and load, reload; the mouse's controls.
void buttons(Viewer& viewer) {
  if (ImGui::Button("Frame G")) viewer.key(Key::G);
  tip("frame the clouds in the part of the view the panel leaves free");
  ImGui::SameLine();
  if (ImGui::Button("Home H")) viewer.key(Key::H);
  ImGui::SameLine();
  if (ImGui::Button("Shot F12")) viewer.key(Key::F12);
  tip("screenshot: nimbus-NNNN.exr and .png");
  if (ImGui::Button("Save ^S")) viewer.key(Key::CtrlS);
  tip("save the view state (Ctrl+S)");
  ImGui::SameLine();
  if (ImGui::Button("Load ^O")) viewer.key(Key::CtrlO);
  tip("load the view state (Ctrl+O)");
  ImGui::SameLine();
  if (ImGui::Button("Save sky")) viewer.save_sky("nimbus-sky.json");
  tip("the clouds, wind and sun as nimbus-sky.json, for --sky");
  ImGui::SameLine();
  if (ImGui::Button("F5")) viewer.key(Key::F5);
  tip("reload the shaders from the source tree");
  ImGui::TextDisabled("drag: turn, right drag: pan,");
  ImGui::TextDisabled("wheel: zoom, Tab: fly (WASD)");
}

}  // namespace

void draw_panel(Viewer& viewer, PanelState& panel) {
  render::ViewState& s = viewer.state();
  const FrameReport& r = viewer.report();
  shader_error_window(viewer.shader_error());
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  // Wide enough for a slider and its longest label whole (a quarter of a 640-pixel window clipped
  // them to "elevat"), never wider than the window.
  const ImGuiStyle& style = ImGui::GetStyle();
  const float label_w = ImGui::CalcTextSize(kLongestLabel).x + style.ItemInnerSpacing.x + 2.0f * style.WindowPadding.x;
  const float min_w = std::min(display.x, label_w + kMinSliderWidth);
  ImGui::SetNextWindowSize(ImVec2(std::max(min_w, std::floor(display.x * kPanelShare)), 0.0f), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSizeConstraints(ImVec2(min_w, 60.0f), ImVec2(display.x, std::max(60.0f, display.y - 16.0f)));
  ImGui::SetNextWindowBgAlpha(kPanelAlpha);
  // Collapsed (its arrow, or a double click on its title) it covers nothing: G then uses the whole view.
  const bool open = ImGui::Begin("nimbus");
  viewer.set_covered_left(open ? ImGui::GetWindowPos().x + ImGui::GetWindowSize().x : 0.0);
  if (!open) {
    ImGui::End();
    return;
  }
  // The sliders take what the longest label leaves.
  ImGui::PushItemWidth(std::max(kMinSliderWidth, ImGui::GetWindowWidth() - label_w));
  status_lines(viewer, r);
  if (ImGui::CollapsingHeader("Time")) time_section(s, r);
  if (ImGui::CollapsingHeader("Sun", ImGuiTreeNodeFlags_DefaultOpen)) sun_section(viewer, panel, s);
  if (ImGui::CollapsingHeader("Clouds")) clouds_section(panel, s);
  if (ImGui::CollapsingHeader("Cloud optics")) optics_section(s);
  if (ImGui::CollapsingHeader("Renderer")) renderer_section(viewer, s);
  if (ImGui::CollapsingHeader("Frame times")) frame_times_section(s, r);
  buttons(viewer);
  ImGui::PopItemWidth();
  ImGui::End();
}

}  // namespace nimbus::viewer
