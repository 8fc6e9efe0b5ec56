// The slicer's settings check and their metadata (cloud_slice_settings.hpp).
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "nimbus/render/core/cloud_slice_settings.hpp"

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
  if (s.slices < 2 || s.slices > 4096)
    throw std::invalid_argument("slice settings slices: must be in [2, 4096], got " + std::to_string(s.slices));
  if (s.light_res < 16 || s.light_res > 4096)
    throw std::invalid_argument("slice settings light_res: must be in [16, 4096], got " + std::to_string(s.light_res));
  // A cone of half-angle pi/2 or more has no finite radius.
  if (!std::isfinite(s.blur_cone_rad) || s.blur_cone_rad < 0.0 || !(s.blur_cone_rad < 0.5 * M_PI))
    throw std::invalid_argument("slice settings blur_cone_rad: must be in [0, pi/2), got " +
                                std::to_string(s.blur_cone_rad));
  if (s.branch != CloudSliceSettings::Branch::Auto && s.branch != CloudSliceSettings::Branch::FrontToBack &&
      s.branch != CloudSliceSettings::Branch::BackToFront)
    throw std::invalid_argument("slice settings branch: not one of auto, front-to-back, back-to-front");
  if (s.max_lights < 1 || s.max_lights > 8)
    throw std::invalid_argument("slice settings max_lights: must be in [1, 8], got " + std::to_string(s.max_lights));
  if (!(s.repeat_to_m >= 0.0 && s.repeat_to_m <= kMaxRepeatToM))
    throw std::invalid_argument("slice settings repeat_to_m: must be in [0, " + number_text(kMaxRepeatToM) + "] metres, got " +
                                number_text(s.repeat_to_m));
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
