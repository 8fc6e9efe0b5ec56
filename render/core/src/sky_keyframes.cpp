// Keyframes of a sky's evolution on a background thread (sky_keyframes.hpp).
#include "nimbus/render/core/sky_keyframes.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nimbus/base/memory.hpp"
#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/up_axis.hpp"
#include "nimbus/volume/vdb_read.hpp"

namespace nimbus::render {
namespace {

// nimbus's volumes are z-up, its renderer y-up: (x, y, z) -> (x, z, -y) (volume/up_axis.hpp).
glm::dvec3 z_up_to_y_up(const glm::dvec3& v) { return {v.x, v.z, -v.y}; }

constexpr int kKeep = 6;  // keyframes held at most (two for the frame, the rest ahead or behind)

}  // namespace

SkyKeyframes::SkyKeyframes(volume::Sky sky, const CloudOptics& optics) : sky_(std::move(sky)), optics_(optics) {
  volume::validate(sky_);
  validate(optics_);
  uint64_t voxels = 0;
  for (std::size_t i = 0; i < sky_.clouds.size(); ++i) {
    CloudSlot s;
    s.name = sky_.clouds[i].preset + " #" + std::to_string(i);
    s.params = volume::sky_cloud_params(sky_, i);
    const double v = sky_.voxel_size_m;
    // The model's bounds (time-independent without wind) in z-up voxel indices, one voxel of
    // margin; voxel (i, j, k) is centred at (i, j, k) * v (volume/generate.hpp).
    const volume::Aabb b = volume::CloudModel(s.params, v, 0.0).bounds();
    if (b.empty()) throw std::invalid_argument("sky clouds[" + std::to_string(i) + "]: the cloud has no extent");
    const openvdb::Coord lo(static_cast<int>(std::floor(b.lo.x / v)) - 1, static_cast<int>(std::floor(b.lo.y / v)) - 1,
                            static_cast<int>(std::floor(b.lo.z / v)) - 1);
    const openvdb::Coord hi(static_cast<int>(std::ceil(b.hi.x / v)) + 1, static_cast<int>(std::ceil(b.hi.y / v)) + 1,
                            static_cast<int>(std::ceil(b.hi.z / v)) + 1);
    // (i, j, k) -> (i, k, -j), as rotate_z_up_to_y_up moves voxels.
    s.box_y = openvdb::CoordBBox(openvdb::Coord(lo.x(), lo.z(), -hi.y()), openvdb::Coord(hi.x(), hi.z(), -lo.y()));
    voxels += s.box_y.volume();
    // The y-up transform of a grid generated at this voxel size, moved to the sky position.
    openvdb::FloatGrid::Ptr empty = openvdb::FloatGrid::create(0.0f);
    empty->setTransform(openvdb::math::Transform::createLinearTransform(v));
    s.transform = volume::rotate_z_up_to_y_up(*empty)->transform().copy();
    const glm::dvec3 p = z_up_to_y_up(sky_.clouds[i].position_m);
    s.transform->postTranslate(openvdb::Vec3d(p.x, p.y, p.z));
    slots_.push_back(std::move(s));
  }
  // Held at once: kKeep keyframes of every box, plus the two copies a pair hands out.
  ensure_fits_in_memory(voxels * (kKeep + 2), sizeof(float), "the sky's keyframes");
  worker_ = std::thread([this] { run(); });
}

SkyKeyframes::~SkyKeyframes() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  stopping_ = true;
  wake_.notify_all();
  worker_.join();
}

int64_t SkyKeyframes::keyframe_at(double t) const {
  return static_cast<int64_t>(std::floor(t / sky_.keyframe_interval_s));
}

double SkyKeyframes::blend_at(double t) const {
  const double x = t / sky_.keyframe_interval_s;
  const double w = x - std::floor(x);
  return w < 1.0 ? w : 0.0;  // rounding can give exactly 1 for tiny negative x
}

void SkyKeyframes::request(int64_t k, int direction) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const int64_t d = direction < 0 ? -1 : 1;
    wanted_ = {k, k + 1, d > 0 ? k + 2 : k - 1, d > 0 ? k + 3 : k - 2};
    // Drop what is far from the frame, keeping the nearest kKeep.
    while (static_cast<int>(frames_.size()) > kKeep) {
      auto far = frames_.begin();
      int64_t worst = -1;
      for (auto it = frames_.begin(); it != frames_.end(); ++it) {
        const int64_t dist = std::abs(it->first - k - (d > 0 ? 1 : 0));
        if (dist > worst) {
          worst = dist;
          far = it;
        }
      }
      frames_.erase(far);
    }
  }
  wake_.notify_all();
}

bool SkyKeyframes::ready(int64_t k) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return frames_.count(k) > 0;
}

void SkyKeyframes::wait(int64_t k) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (frames_.count(k)) return;
  bool listed = false;
  for (int64_t w : wanted_) listed = listed || w == k;
  if (!listed) wanted_.insert(wanted_.begin(), k);
  wake_.notify_all();
  made_.wait(lock, [&] { return frames_.count(k) > 0 || !error_.empty(); });
  if (!error_.empty()) throw std::runtime_error(error_);
}

std::string SkyKeyframes::error() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

SkyKeyframes::Stats SkyKeyframes::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

std::vector<volume::DenseBox> SkyKeyframes::make(int64_t k) const {
  std::vector<volume::DenseBox> boxes;
  volume::GenerateOptions opt;
  opt.voxel_size = sky_.voxel_size_m;
  opt.time = static_cast<double>(k) * sky_.keyframe_interval_s;
  for (const CloudSlot& s : slots_) {
    if (stopping_) throw std::runtime_error("stopped");
    const openvdb::FloatGrid::Ptr grid = volume::generate_density(s.params, opt);
    boxes.push_back(volume::dense_box(*volume::rotate_z_up_to_y_up(*grid), s.box_y));
  }
  return boxes;
}

void SkyKeyframes::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    int64_t next = 0;
    bool found = false;
    wake_.wait(lock, [&] {
      if (stop_ || !error_.empty()) return true;
      for (int64_t w : wanted_) {
        if (!frames_.count(w)) {
          next = w;
          found = true;
          return true;
        }
      }
      return false;
    });
    if (stop_ || !error_.empty()) return;
    if (!found) continue;
    stats_.busy = true;
    lock.unlock();
    const auto start = std::chrono::steady_clock::now();
    std::shared_ptr<const std::vector<volume::DenseBox>> made;
    std::string failure;
    try {
      made = std::make_shared<const std::vector<volume::DenseBox>>(make(next));
    } catch (const std::exception& e) {
      failure = "sky keyframe " + std::to_string(next) + ": " + e.what();
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    lock.lock();
    stats_.busy = false;
    if (made) {
      frames_[next] = made;
      ++stats_.keyframes_made;
      stats_.seconds_total += seconds;
      stats_.seconds_last = seconds;
    } else if (!stop_) {
      error_ = failure;
    }
    made_.notify_all();
  }
}

std::vector<CloudVolume> SkyKeyframes::pair(int64_t k) const {
  std::shared_ptr<const std::vector<volume::DenseBox>> a, b;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto ia = frames_.find(k), ib = frames_.find(k + 1);
    if (ia == frames_.end() || ib == frames_.end())
      throw std::logic_error("sky keyframes " + std::to_string(k) + " and " + std::to_string(k + 1) + " are not both made");
    a = ia->second;
    b = ib->second;
  }
  std::vector<CloudVolume> clouds;
  for (std::size_t i = 0; i < slots_.size(); ++i) {
    volume::DenseBox box = (*a)[i], next = (*b)[i];
    // A keyframe where a cloud has dissolved entirely still needs one value for the slicer's
    // hull; an all-zero box draws nothing either way.
    CloudVolume c = make_cloud_volume(std::move(box), *slots_[i].transform, optics_, slots_[i].name);
    set_next_keyframe(c, std::move(next), 0.0);
    clouds.push_back(std::move(c));
  }
  return clouds;
}

std::vector<CloudMotion> SkyKeyframes::motion(double sky_time_s, const glm::dvec3& wind_m_s, double blend) const {
  if (!std::isfinite(sky_time_s)) throw std::invalid_argument("sky time must be finite");
  const glm::dvec3 drift = z_up_to_y_up(wind_m_s * sky_time_s);
  std::vector<CloudMotion> m(slots_.size());
  for (CloudMotion& x : m) {
    x.offset_m = drift;
    x.blend = blend;
  }
  return m;
}

}  // namespace nimbus::render
