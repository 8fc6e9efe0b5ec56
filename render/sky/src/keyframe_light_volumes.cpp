// Light volumes of a sky's keyframes on a background thread (keyframe_light_volumes.hpp).
#include "nimbus/render/sky/keyframe_light_volumes.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "nimbus/render/reference/light_volume_builder.hpp"

namespace nimbus::render {
namespace {

constexpr std::size_t kKeep = 4;  // volumes held at most: the pair drawn, one ahead, one behind

}  // namespace

KeyframeLightVolumes::KeyframeLightVolumes(std::shared_ptr<SkyKeyframes> keyframes) : keyframes_(std::move(keyframes)) {
  if (!keyframes_) throw std::invalid_argument("keyframe light volumes: no keyframes");
  worker_ = std::thread([this] { run(); });
}

KeyframeLightVolumes::~KeyframeLightVolumes() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

bool KeyframeLightVolumes::use(const KeyframeLight& light) {
  if (has_light_ && light_ == light) return false;
  light_ = light;
  has_light_ = true;
  volumes_.clear();
  return true;
}

bool KeyframeLightVolumes::buildable(int64_t j) const { return keyframes_->ready(j) && keyframes_->ready(j + 1); }

void KeyframeLightVolumes::request(const KeyframeLight& light, int64_t k, int direction) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    use(light);
    wanted_ = {k, k + 1, direction < 0 ? k - 1 : k + 2};
    while (volumes_.size() > kKeep) {
      // Drop the volume farthest from the pair drawn.
      auto far = std::max_element(volumes_.begin(), volumes_.end(), [&](const auto& a, const auto& b) {
        return std::abs(2 * a.first - 2 * k - 1) < std::abs(2 * b.first - 2 * k - 1);
      });
      volumes_.erase(far);
    }
  }
  wake_.notify_all();
}

std::shared_ptr<const LightVolume> KeyframeLightVolumes::get(const KeyframeLight& light, int64_t j) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!has_light_ || !(light_ == light)) return nullptr;
  auto it = volumes_.find(j);
  return it == volumes_.end() ? nullptr : it->second;
}

std::shared_ptr<const LightVolume> KeyframeLightVolumes::wait(const KeyframeLight& light, int64_t j) {
  if (!buildable(j))
    throw std::logic_error("keyframe light volume " + std::to_string(j) + ": keyframes " + std::to_string(j) + " and " +
                           std::to_string(j + 1) + " are not both made");
  std::unique_lock<std::mutex> lock(mutex_);
  if (use(light)) wanted_.clear();
  if (std::find(wanted_.begin(), wanted_.end(), j) == wanted_.end()) wanted_.insert(wanted_.begin(), j);
  wake_.notify_all();
  made_.wait(lock, [&] { return !error_.empty() || (light_ == light && volumes_.count(j) > 0); });
  if (!error_.empty()) throw std::runtime_error(error_);
  return volumes_.at(j);
}

std::string KeyframeLightVolumes::error() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

KeyframeLightVolumes::Stats KeyframeLightVolumes::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

void KeyframeLightVolumes::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    int64_t next = 0;
    wake_.wait(lock, [&] {
      if (stop_ || !error_.empty()) return true;
      for (int64_t w : wanted_)
        if (!volumes_.count(w) && buildable(w)) {
          next = w;
          return true;
        }
      return false;
    });
    if (stop_ || !error_.empty()) return;
    const KeyframeLight light = light_;
    stats_.busy = true;
    lock.unlock();
    const auto start = std::chrono::steady_clock::now();
    std::shared_ptr<const LightVolume> made;
    std::string failure;
    try {
      std::vector<CloudVolume> clouds = keyframes_->pair(next);
      for (CloudVolume& c : clouds) {
        c.optics.extinction_per_m = light.extinction_per_m;
        c.optics.albedo = light.albedo;
        c.optics.phase = light.phase;
      }
      made = std::make_shared<const LightVolume>(
          build_light_volume(clouds, CloudLight{light.direction_to_sun, glm::dvec3(1.0)}, light.settings));
    } catch (const std::exception& e) {
      failure = "light volume of sky keyframe " + std::to_string(next) + ": " + e.what();
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    lock.lock();
    stats_.busy = false;
    if (made) {
      ++stats_.volumes_made;
      stats_.seconds_total += seconds;
      stats_.seconds_last = seconds;
      if (light_ == light) volumes_[next] = made;  // else the light moved on while it was built
    } else if (!stop_) {
      error_ = failure;
    }
    made_.notify_all();
  }
}

}  // namespace nimbus::render
