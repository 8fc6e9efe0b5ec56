// The viewer's panel (view_window.hpp): what the common cloud demos offer (sun, wind, coverage,
// density, optics, steps, an ms/fps line), plus per-pass times and the adaptive quality's choice.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
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

}  // namespace

void draw_panel(Viewer& viewer, PanelState& panel) {
  render::ViewState& s = viewer.state();
  const FrameReport& r = viewer.report();
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(420, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("nimbus");
  ImGui::PushItemWidth(-190.0f);  // room for the labels on the right
  if (r.temporal_frames > 0)
    ImGui::Text("%.1f fps  %.0f ms  (%dx%d, %d slices, quality %d, %u frames accumulated)", r.cpu_ms > 0 ? 1000.0 / r.cpu_ms : 0.0,
                r.cpu_ms, r.info.width, r.info.height, r.info.slices, r.quality_level, r.temporal_frames);
  else
    ImGui::Text("%.1f fps  %.0f ms  (%dx%d, %d slices, quality %d, %u sample%s%s)", r.cpu_ms > 0 ? 1000.0 / r.cpu_ms : 0.0,
                r.cpu_ms, r.info.width, r.info.height, r.info.slices, r.quality_level, r.samples, r.samples == 1 ? "" : "s",
                r.converged ? ", still" : "");
  if (!viewer.message().empty()) ImGui::TextWrapped("%s", viewer.message().c_str());
  if (!viewer.shader_error().empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "%s", viewer.shader_error().c_str());

  if (ImGui::CollapsingHeader("Time", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::Checkbox("paused (Space; Left/Right step)", &s.paused);
    slider("speed (sky s per s)", s.speed, 0.0, 1000.0, "%.1f", true);
    ImGui::Text("sky %.1f s, evolution %.1f s%s", s.sky_time_s, s.evolution_time_s, r.info.waited ? " (waiting)" : "");
  }
  if (ImGui::CollapsingHeader("Sun", ImGuiTreeNodeFlags_DefaultOpen)) {
    double el = s.sky.sun_elevation_deg, az = s.sky.sun_azimuth_deg;
    bool moved = slider("elevation (deg)", el, -10.0, 90.0, "%.1f");
    moved |= slider("azimuth (deg)", az, 0.0, 359.9, "%.1f");
    bool day_moved = slider("time of day (h)", panel.hour, 0.0, 24.0, "%.2f");
    day_moved |= slider("latitude (deg)", panel.latitude_deg, -90.0, 90.0, "%.1f");
    day_moved |= slider("day of year", panel.day_of_year, 1.0, 366.0, "%.0f");
    if (day_moved) {
      // The renderer's suns end 10 degrees below the horizon: night holds the sun there.
      const app::SunPosition sun = app::sun_at(panel.hour, panel.latitude_deg, panel.day_of_year);
      el = std::max(sun.elevation_deg, -10.0);
      az = sun.azimuth_deg;
      moved = true;
    }
    if (moved) viewer.set_sun(el, az);
  }
  if (ImGui::CollapsingHeader("Clouds")) {
    // Edits that need new keyframes apply when the control is released.
    volume::Sky& edit = panel.edit;
    bool& editing = panel.editing;
    if (!editing) edit = s.sky;
    bool done = false;
    const std::vector<volume::PresetInfo>& presets = volume::list_presets();
    for (std::size_t i = 0; i < edit.clouds.size(); ++i) {
      ImGui::PushID(static_cast<int>(i));
      volume::SkyCloud& c = edit.clouds[i];
      if (ImGui::BeginCombo("preset", c.preset.c_str())) {
        for (const auto& p : presets) {
          if (p.genus == "gas") continue;
          if (ImGui::Selectable(p.name.c_str(), p.name == c.preset)) {
            c.preset = p.name;
            c.overrides = nlohmann::json::object();
            done = true;
          }
        }
        ImGui::EndCombo();
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
    if (slider("evolution rate (x preset)", edit.evolution_scale, 0.0, 50.0, "%.2f")) editing = true;
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
    bool wind = slider("wind (m/s)", speed, 0.0, 60.0, "%.1f");
    wind |= slider("wind towards (deg)", towards, 0.0, 359.9, "%.0f");
    if (wind) {
      s.sky.wind_m_s.x = speed * std::sin(towards * kPi / 180.0);
      s.sky.wind_m_s.y = speed * std::cos(towards * kPi / 180.0);
    }
  }
  if (ImGui::CollapsingHeader("Cloud optics")) {
    slider("extinction (/m per density)", s.optics.extinction_per_m, 0.001, 0.5, "%.4f", true);
    double albedo = s.optics.albedo.x;
    if (slider("albedo", albedo, 0.5, 1.0, "%.3f")) s.optics.albedo = glm::dvec3(albedo);
    slider("phase g forward", s.optics.phase.g_forward, 0.0, 0.95);
    slider("phase g back", s.optics.phase.g_back, -0.95, 0.0);
    slider("phase forward weight", s.optics.phase.forward_weight, 0.0, 1.0);
    bool volume = s.slices.multiple.method == render::MultipleScatteringMethod::LightVolume;
    if (ImGui::Checkbox("light volume (photon-traced multiple scattering)", &volume))
      s.slices.multiple.method = volume ? render::MultipleScatteringMethod::LightVolume : render::MultipleScatteringMethod::Octaves;
    if (volume) {
      ImGui::SliderInt("light volume cells", &s.slices.multiple.light_volume.resolution, 16, 96);
      int photons_log2 = static_cast<int>(std::lround(std::log2(static_cast<double>(s.slices.multiple.light_volume.photons))));
      if (ImGui::SliderInt("light volume photons (log2)", &photons_log2, 14, 24)) s.slices.multiple.light_volume.photons = std::int64_t{1} << photons_log2;
    }
    ImGui::SliderInt(volume ? "octaves (until the volume is made)" : "multiple-scattering octaves", &s.slices.multiple.octaves, 0, 3);
  }
  if (ImGui::CollapsingHeader("Renderer", ImGuiTreeNodeFlags_DefaultOpen)) {
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
    slider("exposure (stops)", s.exposure_stops, -6.0, 6.0, "%.2f");
    AdaptiveQuality& a = viewer.adaptive();
    ImGui::Checkbox("adaptive quality", &a.enabled);
    bool temporal = viewer.temporal();
    if (ImGui::Checkbox("accumulate moving frames", &temporal)) viewer.set_temporal(temporal);
    slider("frame budget (ms)", a.budget_ms, 10.0, 1000.0, "%.0f", true);
  }
  if (ImGui::CollapsingHeader("Frame times", ImGuiTreeNodeFlags_DefaultOpen)) {
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
  if (ImGui::Button("Screenshot (F12)")) viewer.key(Key::F12);
  ImGui::SameLine();
  if (ImGui::Button("Save (Ctrl+S)")) viewer.key(Key::CtrlS);
  ImGui::SameLine();
  if (ImGui::Button("Load (Ctrl+O)")) viewer.key(Key::CtrlO);
  if (ImGui::Button("Save sky (nimbus-sky.json)")) viewer.save_sky("nimbus-sky.json");
  ImGui::SameLine();
  if (ImGui::Button("Reload shaders (F5)")) viewer.key(Key::F5);
  ImGui::SameLine();
  if (ImGui::Button("Frame (G)")) viewer.key(Key::G);
  ImGui::SameLine();
  if (ImGui::Button("Home (H)")) viewer.key(Key::H);
  ImGui::TextWrapped("Left drag tumbles, right drag pans, wheel zooms; Tab: fly (WASD, Q/E, Shift).");
  ImGui::PopItemWidth();
  ImGui::End();
}

}  // namespace nimbus::viewer
