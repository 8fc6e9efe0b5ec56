// The binding of the table's settings to the request's fields (request_settings.hpp).
#include "nimbus/render/sky/request_settings.hpp"

#include <cstdint>
#include <stdexcept>

namespace nimbus::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A setting's field: one of three types, and the factor from the table's unit to the field's.
struct SettingField {
  int* i = nullptr;
  std::int64_t* i64 = nullptr;
  double* d = nullptr;
  bool degrees_as_radians = false;
};

// The one line per setting.
SettingField field_of(RenderRequest& r, Setting id) {
  CloudSliceSettings& s = r.slices;
  MultipleScattering& ms = s.multiple;
  switch (id) {
    case Setting::Slices: return {&s.slices};
    case Setting::LightRes: return {&s.light_res};
    case Setting::MaxLights: return {&s.max_lights};
    case Setting::Blur: return {nullptr, nullptr, &s.blur_cone_rad, true};
    case Setting::RepeatTo: return {nullptr, nullptr, &s.repeat_to_m};
    case Setting::CloudShadowRes: return {&r.cloud_shadow_res};
    case Setting::CloudExtinction: return {nullptr, nullptr, &r.optics.extinction_per_m};
    case Setting::Multiple: return {&ms.octaves};
    case Setting::MsGrid: return {&ms.light_volume.resolution};
    case Setting::MsPhotons: return {nullptr, &ms.light_volume.photons};
    case Setting::MsLobes: return {&ms.light_volume.lobe_orders};
    case Setting::MsDiffusionDepth: return {nullptr, nullptr, &ms.light_volume.diffusion_depth};
    case Setting::MsSimilarityDepth: return {nullptr, nullptr, &ms.light_volume.similarity_depth};
    case Setting::MsOcclusion: return {nullptr, nullptr, &ms.occlusion};
    case Setting::MsContribution: return {nullptr, nullptr, &ms.contribution};
    case Setting::MsEccentricity: return {nullptr, nullptr, &ms.eccentricity};
    case Setting::Fov: return {nullptr, nullptr, &r.camera.fov_deg};
    case Setting::Exposure: return {nullptr, nullptr, &r.exposure_stops};
    case Setting::RenderScale: return {nullptr, nullptr, &r.render_scale};
    case Setting::Speed:
    case Setting::Count: break;
  }
  return {};
}

SettingField checked_field(RenderRequest& r, Setting id) {
  const SettingField f = field_of(r, id);
  if (!f.i && !f.i64 && !f.d)
    throw std::logic_error("render setting '" + std::string(setting(id).view_key) + "' is not a field of the request");
  return f;
}

}  // namespace

bool in_request(Setting id) { return id != Setting::Speed && id != Setting::Count; }

double setting_value(const RenderRequest& request, Setting id) {
  const SettingField f = checked_field(const_cast<RenderRequest&>(request), id);  // read only
  if (f.i) return *f.i;
  if (f.i64) return double(*f.i64);
  return f.degrees_as_radians ? *f.d * 180.0 / kPi : *f.d;
}

void set_setting_value(RenderRequest& request, Setting id, double value, const std::string& name) {
  const SettingField f = checked_field(request, id);
  check_setting(id, value, name);  // in range, so an integer setting's value fits its field
  if (f.i) *f.i = int(value);
  else if (f.i64) *f.i64 = std::int64_t(value);
  else *f.d = f.degrees_as_radians ? value * kPi / 180.0 : value;
}

void set_setting_defaults(RenderRequest& request, SettingDefaults which) {
  for (const RenderSetting& s : kRenderSettings)
    if (in_request(s.id))
      set_setting_value(request, s.id, which == SettingDefaults::Still ? s.still_default : s.view_default,
                        std::string(s.view_key));
}

Setting setting_at_view_key(const std::string& section, const std::string& key) {
  const std::string full = section + "." + key;
  for (const RenderSetting& s : kRenderSettings)
    if (s.view_key == full) return s.id;
  return Setting::Count;
}

}  // namespace nimbus::render
