// The slicer's settings check and their metadata (cloud_slice_settings.hpp).
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "nimbus/render/core/cloud_slice_settings.hpp"
#include "nimbus/render/core/render_settings.hpp"

#include "nimbus/base/validate.hpp"

namespace nimbus::render {
namespace {

const char* branch_name(CloudSliceSettings::Branch b) {
  switch (b) {
    case CloudSliceSettings::Branch::FrontToBack: return "front-to-back";
    case CloudSliceSettings::Branch::BackToFront: return "back-to-front";
    default: return "auto";
  }
}

}  // namespace

void validate(const CloudSliceSettings& s) {
  check_setting(Setting::Slices, s.slices, "slice settings slices");
  check_setting(Setting::LightRes, s.light_res, "slice settings light_res");
  // A cone of half-angle pi/2 or more has no finite radius (the table's blur is in degrees).
  check_setting(Setting::Blur, s.blur_cone_rad * 180.0 / M_PI, "slice settings blur_cone_rad (in degrees)");
  if (s.branch != CloudSliceSettings::Branch::Auto && s.branch != CloudSliceSettings::Branch::FrontToBack &&
      s.branch != CloudSliceSettings::Branch::BackToFront)
    throw std::invalid_argument("slice settings branch: not one of auto, front-to-back, back-to-front");
  check_setting(Setting::MaxLights, s.max_lights, "slice settings max_lights");
  check_setting(Setting::RepeatTo, s.repeat_to_m, "slice settings repeat_to_m");
  try {
    validate(s.multiple);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("slice settings multiple: ") + e.what());
  }
}

void describe_slices(Image& image, const CloudSliceSettings& settings) {
  const CloudSliceSettings& s = settings;
  std::ostringstream o;
  o.precision(9);
  o << s.slices << " slices, light buffer " << s.light_res << "^2, jitter " << (s.jitter ? "on" : "off") << " frame "
    << s.frame << ", ambient " << (s.ambient ? "on" : "off") << ", blur_cone_rad " << s.blur_cone_rad
    << ", multiple scattering " << to_string(s.multiple.method);
  if (s.multiple.method == MultipleScatteringMethod::LightVolume)
    o << " (resolution " << s.multiple.light_volume.resolution << ", photons " << s.multiple.light_volume.photons
      << ", seed " << s.multiple.light_volume.seed << ")";
  else
    o << ", octaves " << s.multiple.octaves << " (occlusion " << s.multiple.occlusion << " contribution "
      << s.multiple.contribution << " eccentricity " << s.multiple.eccentricity << ")";
  o << ", branch " << branch_name(s.branch) << ", max_lights " << s.max_lights;
  if (s.repeat_to_m > 0.0) o << ", periodic tiles repeated to " << s.repeat_to_m << " m";
  image.metadata["slices"] = o.str();
}

}  // namespace nimbus::render
