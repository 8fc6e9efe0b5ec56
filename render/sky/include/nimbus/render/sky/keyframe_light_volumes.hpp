// The light volumes (light_volume.hpp) of an animated sky's keyframes, built on a background
// thread so that a render loop never waits on the photon tracer (seconds per volume). Keyframe
// j's volume is that of SkyKeyframes::pair(j) at blend 0: its own density, on the box of j and
// j + 1, at its sky position without the wind (the wind moves the clouds and their light as one:
// the sky renderer shifts the volume). Every volume is for one light (KeyframeLight); asking under
// a new one drops the old one's volumes and stops the build under the old one at once (the worker
// turns to the new light). Each build starts from its keyframe's setup (LightVolumeSetup: the grid,
// the media and the covered cells, whatever the sun), made once and kept for the keyframes near
// the one drawn: a new sun over the same clouds pays only for its photons.
#pragma once
#include <cstdint>
#include <memory>
#include <deque>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/light_volume.hpp"
#include "nimbus/render/sky/keyframe_worker.hpp"
#include "nimbus/render/sky/sky_keyframes.hpp"

namespace nimbus::render {
class LightVolumeSetup;
}

namespace nimbus::render {

// What a keyframe's volume depends on besides its density.
struct KeyframeLight {
  glm::dvec3 direction_to_sun{0.0, 1.0, 0.0};  // unit
  double extinction_per_m = 0.04;
  glm::dvec3 albedo{0.99};
  Phase phase;
  LightVolumeSettings settings;
  // The same optics (the clouds' media): a kept keyframe density serves both.
  bool same_optics(const KeyframeLight& o) const {
    return extinction_per_m == o.extinction_per_m && albedo == o.albedo && phase == o.phase;
  }
  bool operator==(const KeyframeLight& o) const {
    return direction_to_sun == o.direction_to_sun && same_optics(o) && settings == o.settings;
  }
};

class KeyframeLightVolumes {
 public:
  explicit KeyframeLightVolumes(std::shared_ptr<SkyKeyframes> keyframes);
  ~KeyframeLightVolumes();  // stops the worker after the volume it is building
  KeyframeLightVolumes(const KeyframeLightVolumes&) = delete;
  KeyframeLightVolumes& operator=(const KeyframeLightVolumes&) = delete;

  const std::shared_ptr<SkyKeyframes>& keyframes() const { return keyframes_; }

  // Wants the volumes of keyframes k and k + 1, then k + 2 (k - 1 when `direction` < 0), under
  // `light`; a volume is built once its keyframe pair is made, so a render loop asks every
  // frame. `count` < 3 wants only the first ones of those (1: keyframe k's alone, a new sun's
  // quick first volume). Never blocks.
  void request(const KeyframeLight& light, int64_t k, int direction = 1, int count = 3);
  // Keyframe j's volume under `light`, or null while it is not made.
  std::shared_ptr<const LightVolume> get(const KeyframeLight& light, int64_t j) const;
  // Blocks until it is made. Keyframes j and j + 1 must be made (std::logic_error otherwise);
  // rethrows the worker's error (std::runtime_error).
  std::shared_ptr<const LightVolume> wait(const KeyframeLight& light, int64_t j);
  std::string error() const { return worker_.error(); }
  // Volumes built (made), seconds building them, builds stopped by a new light, and whether one
  // is being built.
  KeyframeWorkerStats stats() const { return worker_.stats(); }

 private:
  bool buildable(int64_t j) const;  // its keyframe pair is made
  LightVolume build(int64_t j, const KeyframeLight& light);  // on the worker thread
  // Keyframe j's setup for `light` (its direction aside): a kept one that fits, or a new one.
  std::shared_ptr<const LightVolumeSetup> setup(int64_t j, const KeyframeLight& light);

  // The setups kept (the worker thread's alone), oldest first: keyframe j's clouds with the
  // light's optics, and their setup for its settings.
  struct KeptSetup {
    int64_t j = 0;
    KeyframeLight light;  // direction and photons aside
    std::shared_ptr<const std::vector<CloudVolume>> clouds;
    std::shared_ptr<const LightVolumeSetup> setup;
  };
  std::deque<KeptSetup> setups_;

  std::shared_ptr<SkyKeyframes> keyframes_;
  KeyframeWorker<LightVolume, KeyframeLight> worker_;  // last: its thread reads keyframes_
};

}  // namespace nimbus::render
