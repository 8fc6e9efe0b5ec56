// Light volumes of a sky's keyframes on a background thread (keyframe_light_volumes.hpp).
#include "nimbus/render/sky/keyframe_light_volumes.hpp"

#include <stdexcept>
#include <utility>
#include <vector>

#include "nimbus/render/reference/light_volume_builder.hpp"

namespace nimbus::render {
namespace {

constexpr std::size_t kKeep = 4;  // volumes held at most: the pair drawn, one ahead, one behind

// Keyframe j's volume: the pair (j, j + 1) at blend 0 with the light's optics, lit by a unit sun.
LightVolume build_keyframe_volume(const SkyKeyframes& keyframes, int64_t j, const KeyframeLight& light) {
  std::vector<CloudVolume> clouds = keyframes.pair(j);
  for (CloudVolume& c : clouds) {
    c.optics.extinction_per_m = light.extinction_per_m;
    c.optics.albedo = light.albedo;
    c.optics.phase = light.phase;
  }
  return build_light_volume(clouds, Light{light.direction_to_sun, glm::dvec3(1.0)}, light.settings);
}

}  // namespace

KeyframeLightVolumes::KeyframeLightVolumes(std::shared_ptr<SkyKeyframes> keyframes)
    : keyframes_(keyframes ? std::move(keyframes) : throw std::invalid_argument("keyframe light volumes: no keyframes")),
      worker_(
          "light volume of sky keyframe",
          [this](int64_t j, const KeyframeLight& light) { return build_keyframe_volume(*keyframes_, j, light); },
          [this](int64_t j) { return buildable(j); }) {}

KeyframeLightVolumes::~KeyframeLightVolumes() = default;

bool KeyframeLightVolumes::buildable(int64_t j) const { return keyframes_->ready(j) && keyframes_->ready(j + 1); }

void KeyframeLightVolumes::request(const KeyframeLight& light, int64_t k, int direction) {
  // Held: the pair drawn, one ahead and one behind, nearest the middle of the pair.
  worker_.want(light, {k, k + 1, direction < 0 ? k - 1 : k + 2}, 2 * k + 1, kKeep);
}

std::shared_ptr<const LightVolume> KeyframeLightVolumes::get(const KeyframeLight& light, int64_t j) const {
  return worker_.get(light, j);
}

std::shared_ptr<const LightVolume> KeyframeLightVolumes::wait(const KeyframeLight& light, int64_t j) {
  if (!buildable(j))
    throw std::logic_error("keyframe light volume " + std::to_string(j) + ": keyframes " + std::to_string(j) + " and " +
                           std::to_string(j + 1) + " are not both made");
  return worker_.wait(light, j);
}

}  // namespace nimbus::render
