// Light volumes of a sky's keyframes on a background thread (keyframe_light_volumes.hpp).
#include "nimbus/render/sky/keyframe_light_volumes.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>
#include <vector>

#include "nimbus/render/reference/light_volume_builder.hpp"

namespace nimbus::render {
namespace {

constexpr std::size_t kKeep = 4;  // volumes held at most: the pair drawn, one ahead, one behind
// Setups kept at most: the three keyframes wanted, under a full and a quick light. Each holds
// its keyframe pair's density (tens of MB on the default sky); the two lights share it.
constexpr std::size_t kKeepSetups = 6;

// What a setup depends on besides the keyframe: the light without its direction and photons.
KeyframeLight setup_key(KeyframeLight light) {
  light.direction_to_sun = glm::dvec3(0.0);
  light.settings.photons = 0;
  light.settings.seed = 0;
  return light;
}

}  // namespace

KeyframeLightVolumes::KeyframeLightVolumes(std::shared_ptr<SkyKeyframes> keyframes)
    : keyframes_(keyframes ? std::move(keyframes) : throw std::invalid_argument("keyframe light volumes: no keyframes")),
      worker_(
          "light volume of sky keyframe", [this](int64_t j, const KeyframeLight& light) { return build(j, light); },
          [this](int64_t j) { return buildable(j); }) {}

std::shared_ptr<const LightVolumeSetup> KeyframeLightVolumes::setup(int64_t j, const KeyframeLight& light) {
  const KeyframeLight key = setup_key(light);
  std::shared_ptr<const std::vector<CloudVolume>> clouds;
  for (const KeptSetup& kept : setups_) {
    if (kept.j != j || !kept.light.same_optics(key)) continue;
    if (kept.light == key && kept.setup->fits(light.settings)) return kept.setup;
    clouds = kept.clouds;  // the same density and optics under other settings
  }
  if (!clouds) {
    // Keyframe j's volume: the pair (j, j + 1) at blend 0 with the light's optics.
    std::vector<CloudVolume> pair = keyframes_->pair(j);
    for (CloudVolume& c : pair) {
      c.optics.extinction_per_m = light.extinction_per_m;
      c.optics.albedo = light.albedo;
      c.optics.phase = light.phase;
    }
    clouds = std::make_shared<const std::vector<CloudVolume>>(std::move(pair));
  }
  auto made = std::make_shared<const LightVolumeSetup>(clouds, light.settings);
  setups_.push_back({j, key, clouds, made});
  if (setups_.size() > kKeepSetups) setups_.pop_front();
  return made;
}

// Keyframe j's volume, lit by a unit sun from the light's direction.
LightVolume KeyframeLightVolumes::build(int64_t j, const KeyframeLight& light) {
  LightVolumeBuild b(setup(j, light), Light{light.direction_to_sun, glm::dvec3(1.0)}, light.settings);
  b.trace(light.settings.photons);
  return b.volume();
}

KeyframeLightVolumes::~KeyframeLightVolumes() = default;

bool KeyframeLightVolumes::buildable(int64_t j) const { return keyframes_->ready(j) && keyframes_->ready(j + 1); }

void KeyframeLightVolumes::request(const KeyframeLight& light, int64_t k, int direction, int count) {
  // Held: the pair drawn, one ahead and one behind, nearest the middle of the pair.
  std::vector<int64_t> keys = {k, k + 1, direction < 0 ? k - 1 : k + 2};
  keys.resize(static_cast<std::size_t>(std::clamp(count, 1, 3)));
  worker_.want(light, std::move(keys), 2 * k + 1, kKeep);
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
