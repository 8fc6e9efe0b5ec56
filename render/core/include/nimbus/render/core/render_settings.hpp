// The one table of the render settings the front ends share: each value's name on the command
// line (`nimbus render --NAME`, and Python's `render(NAME=...)` with dashes as underscores), its
// key in a view state, its unit, its range, its defaults and its help text. The library's
// validators, the CLI's flags, the view state's reader and Python's signature all read it, and a
// test checks each front end against it (docs/architecture.md, "Adding a render setting").
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace nimbus::render {

enum class Setting {
  Slices, LightRes, MaxLights, Blur, RepeatTo, CloudShadowRes, CloudExtinction, Multiple, MsGrid, MsPhotons, MsLobes,
  MsDiffusionDepth, MsSimilarityDepth, MsOcclusion, MsContribution, MsEccentricity, Fov, Exposure, Speed, RenderScale,
  Count
};

struct RenderSetting {
  Setting id;
  std::string_view flag;      // `nimbus render --flag`; Python's keyword with '_' for '-'; empty: the viewer's own
  std::string_view view_key;  // "renderer.slices" in a view state; empty: not held there
  std::string_view unit;      // printed after the range: "cells", "metres", "" for a plain number
  bool integer;               // an integer setting (the CLI and the JSON take no fraction)
  double min, max;            // the range, closed unless min_open / max_open
  bool min_open, max_open;
  // The default of a still (`nimbus render`, Python); `default_text` says it in words where it
  // depends on the rest of the render (then `still_default` is the value it most often takes).
  double still_default;
  std::string_view default_text;
  // The viewer's default (its view state's), where the viewer trades error for speed; `view_reason`
  // says why it differs from the still's (empty when it does not).
  double view_default;
  std::string_view view_reason;
  std::string_view help;
};

inline constexpr double kPhotonsMax = double(std::int64_t{1} << 28);

// In Setting's order (a static_assert in render_settings.cpp checks it).
inline constexpr std::array<RenderSetting, std::size_t(Setting::Count)> kRenderSettings{{
    {Setting::Slices, "slices", "renderer.slices", "", true, 2, 4096, false, false, 128, "", 128, "",
     "Half-angle slices across the clouds"},
    {Setting::LightRes, "light-res", "renderer.light_res", "texels", true, 16, 4096, false, false, 256, "", 256, "",
     "Light buffer size, texels per side"},
    {Setting::MaxLights, "max-lights", "", "", true, 1, 8, false, false, 4, "", 4, "",
     "Lights the slicer draws, one pass each: the strongest at the clouds"},
    {Setting::Blur, "blur", "", "degrees", false, 0, 90, false, true, 0, "", 0, "",
     "Forward-scattering blur cone half-angle (0: off)"},
    {Setting::RepeatTo, "repeat-to", "renderer.repeat_to", "metres", false, 0, 1e6, false, false, 32000,
     "auto: 32000 under --scene sky, else 0, one tile", 32000, "",
     "A periodic field (cumulus-field, stratocumulus-field) is drawn with copies of its tile out to this distance "
     "from the eye, to the horizon"},
    {Setting::CloudShadowRes, "cloud-shadow-res", "renderer.cloud_shadow_res", "texels", true, 16, 8192, false, false,
     512, "", 256, "drawn again every frame in the viewer", "Texels per side of the clouds' shadow on the scene"},
    {Setting::CloudExtinction, "cloud-extinction", "optics.extinction", "per metre", false, 0, 1e12, false, false,
     0.04, "0.04, or a scene's own gas, as steam-lamp's", 0.04, "", "Cloud extinction per unit density"},
    {Setting::Multiple, "multiple", "optics.multiple", "octaves", true, 0, 3, false, false, 0,
     "the light volume where there is a sun, else 0 octaves", 2,
     "the octaves drawn while the first light volume is being built",
     "Multiple scattering: 0 = single scattering; octaves 1-3 (the octaves method, unless --ms-method "
     "light-volume, which takes 1 = on)"},
    {Setting::MsGrid, "ms-grid", "optics.ms_grid", "cells", true, 4, 192, false, false, 48, "", 48, "",
     "Light volume: cells along the clouds' longest axis at least (finer where its photons allow: about 1000 a "
     "cell)"},
    {Setting::MsPhotons, "ms-photons", "optics.ms_photons", "photons", true, 1, kPhotonsMax, false, false,
     double(1 << 21), "", double(1 << 19), "a keyframe's light volume in about half a second on 2 cores",
     "Light volume: photons from the sun"},
    {Setting::MsLobes, "ms-lobes", "", "orders", true, 0, 2, false, false, 2, "", 2, "",
     "Light volume: scattering orders kept as lobes about the sun (0: harmonics alone)"},
    {Setting::MsDiffusionDepth, "ms-diffusion-depth", "", "transport mean free paths", false, 0, 1000, false, false,
     0, "", 0, "",
     "Light volume: deeper than this inside the clouds, photons hand their light to a diffusion solve on its grid "
     "(0: photons carry all of it)"},
    {Setting::MsSimilarityDepth, "ms-similarity-depth", "", "transport mean free paths", false, 0, 1000, false,
     false, 0, "", 0, "",
     "Light volume: deeper than this inside the clouds, photons past their lobe orders fly in the similar medium "
     "(isotropic, sigma_s (1 - g)) (0: the true phase everywhere)"},
    {Setting::MsOcclusion, "ms-occlusion", "", "", false, 0, 1, true, false, 0.5, "", 0.5, "",
     "Multiple-scattering octaves: extinction scale a per octave"},
    {Setting::MsContribution, "ms-contribution", "", "", false, 0, 1, false, false, 0.5, "", 0.5, "",
     "Multiple-scattering octaves: radiance scale b per octave"},
    {Setting::MsEccentricity, "ms-eccentricity", "", "", false, 0, 1, false, false, 0.5, "", 0.5, "",
     "Multiple-scattering octaves: phase asymmetry scale c per octave"},
    // Below 1 degree a framed camera stands hundreds of kilometres from its clouds, beyond the
    // sky's atmosphere (an all-black picture); at 180 the projection has no extent.
    {Setting::Fov, "fov", "camera.fov", "degrees", false, 1, 179, false, false, 60,
     "the scene's camera's, 60, or 44.8 with --scene none, as vdb_render", 60, "",
     "Horizontal field of view"},
    {Setting::Exposure, "exposure", "renderer.exposure", "stops", false, -64, 64, false, false, 0,
     "automatic, from the picture", 0, "the display's exposure, set by hand",
     "The preview's exposure: radiance times 2^stops"},
    {Setting::Speed, "", "time.speed", "sky seconds per second", false, 0, 1000, false, false, 10, "", 10, "",
     "How fast the viewer's sky time runs"},
    {Setting::RenderScale, "", "renderer.render_scale", "", false, 0.01, 1, false, false, 1, "", 1, "",
     "The viewer renders at this share of its window's size"},
}};

constexpr const RenderSetting& setting(Setting id) { return kRenderSettings[std::size_t(id)]; }

// True when `value` is within the setting's range (so finite: a NaN fails every comparison, an
// infinity the bound), and whole for an integer setting. Constexpr: the table's own defaults are
// checked with it at compile time (render_settings.cpp).
constexpr bool in_range(const RenderSetting& s, double v) {
  if (s.min_open ? !(v > s.min) : !(v >= s.min)) return false;
  if (s.max_open ? !(v < s.max) : !(v <= s.max)) return false;
  return !s.integer || v == double(std::int64_t(v));  // within the range, so the cast is defined
}
// "[4, 192] cells", "(0, 1]", "[0, 90) degrees".
std::string range_text(const RenderSetting& s);
// Throws std::invalid_argument "<name>: must be in <range_text>, got <value>" unless in_range.
void check_setting(Setting id, double value, const std::string& name);
// "--slices" (empty for a setting with no flag).
std::string flag_name(const RenderSetting& s);

}  // namespace nimbus::render
