// The table of `nimbus render`'s flags and the modes they apply to (render_modes.hpp).
#include "render_modes.hpp"

#include "flag_checks.hpp"
#include "setting_flags.hpp"

namespace nimbus::cli {

void check_render_flags(const CLI::App& render, RenderMode mode) {
  constexpr unsigned all = kRenderScene | kRenderClouds | kRenderViewState;
  constexpr unsigned scene = kRenderScene, clouds = kRenderClouds, view = kRenderViewState;
  constexpr unsigned placed = kRenderScene | kRenderClouds;  // a scene or clouds the flags place
  static const std::vector<FlagModes> table = [] {
    std::vector<FlagModes> t = {
      // Every mode: the image and its preview.
      {"--output", all}, {"--res", all}, {"--preview", all}, {"--exposure", all},
      {"--view-state", view},
      // A scene, alone or under clouds, and the camera the flags place.
      {"--scene", placed}, {"--method", placed}, {"--no-surface-airlight", placed},
      {"--eye", placed}, {"--look-at", placed}, {"--up", placed}, {"--fov", placed},
      // The light-shaft renderer of a scene alone (under clouds the scene's method is --shafts).
      {"--jitter", scene}, {"--shadow-res", scene}, {"--extinction", scene}, {"--albedo", scene},
      {"--phase", scene}, {"--hide-bulbs", scene},
      // Clouds (add_cloud_render_options).
      {"file", clouds}, {"--request", clouds}, {"--preset", clouds}, {"--grid", clouds}, {"--up-axis", clouds}, {"--level-set-to-fog", clouds},
      {"--voxel-size", clouds}, {"--time", clouds}, {"--frames", clouds}, {"--fps", clouds}, {"--time-scale", clouds},
      {"--many-frames", clouds}, {"--start-frame", clouds},
      {"--frame-from-env", clouds}, {"--chunk", clouds}, {"--sun", clouds}, {"--sun-elevation", clouds}, {"--sun-azimuth", clouds}, {"--time-of-day", clouds},
      {"--latitude", clouds}, {"--day-of-year", clouds}, {"--lamp", clouds}, {"--lamp-intensity", clouds},
      {"--spot", clouds}, {"--spot-cone", clouds}, {"--shafts", clouds}, {"--cloud-albedo", clouds},
      {"--cloud-phase", clouds}, {"--ambient", clouds}, {"--ms-method", clouds}, {"--ms-seed", clouds},
      {"--no-jitter", clouds}, {"--no-grain-filter", clouds | view}, {"--spp", clouds | view}, {"--bounces", clouds},
      {"--seed", clouds},
    };
    // The table's numbers that are the clouds' (setting_flags.hpp): --slices, --ms-photons...
    for (const render::RenderSetting& s : render::kRenderSettings)
      if (is_cloud_setting(s.id)) t.push_back({render::flag_name(s), clouds});
    return t;
  }();
  static const std::vector<std::string> names = {"a scene alone", "clouds (FILE.vdb or --preset)",
                                                 "a view state (--view-state)"};
  check_flags_apply(render, table, mode, names);
}

}  // namespace nimbus::cli
