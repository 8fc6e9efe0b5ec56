// Keyframes of a sky's evolution on a background thread (sky_keyframes.hpp).
#include "nimbus/render/sky/sky_keyframes.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <cstdio>
#include <filesystem>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nimbus/base/file_kind.hpp"
#include "nimbus/base/input_limits.hpp"
#include "nimbus/base/memory.hpp"
#include "nimbus/render/core/cloud_source.hpp"
#include "nimbus/render/core/world_axes.hpp"
#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/vdb_read.hpp"

namespace nimbus::render {
namespace {

// nimbus's volumes are z-up, its renderer y-up: (x, y, z) -> (x, z, -y) (volume/up_axis.hpp).
glm::dvec3 z_up_to_y_up(const glm::dvec3& v) { return {v.x, v.z, -v.y}; }

constexpr std::size_t kKeep = 6;  // keyframes held at most (two for the frame, the rest ahead or behind)

}  // namespace

std::vector<int> existing_sequence_frames(const std::string& file) {
  const SequencePattern pattern = SequencePattern::parse(file, "sky cloud file");
  std::vector<int> frames;
  for (int n = 0; n <= 99999; ++n) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(pattern.path(n), ec)) frames.push_back(n);
  }
  if (frames.empty())
    throw std::runtime_error("sky cloud file '" + echo(file, 300) + "': no frame of the sequence exists (frames 0 to 99999 as regular files)");
  return frames;
}

void require_cloud_file(const std::string& file) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) throw std::runtime_error("sky cloud file '" + echo(file, 300) + "': " + std::strerror(errno));
  if (!S_ISREG(st.st_mode))
    throw std::runtime_error("sky cloud file '" + echo(file, 300) + "': is " + file_kind(st.st_mode) + ", not a VDB file");
}

void check_sky_cloud_files(const volume::Sky& sky) {
  for (const volume::SkyCloud& c : sky.clouds) {
    if (c.file.empty()) continue;
    if (SequencePattern::parse(c.file, "sky cloud file").has_field) existing_sequence_frames(c.file);
    else require_cloud_file(c.file);
  }
}

SkyKeyframes::SkyKeyframes(volume::Sky sky, const CloudOptics& optics)
    : sky_(std::move(sky)), optics_(optics), worker_("sky keyframe", [this](int64_t k, KeyframeWorkerNoContext) { return make(k); }) {
  volume::validate(sky_);
  validate(optics_);
  interval_s_ = sky_.keyframe_interval_s;
  bool sequence_timed = false;
  uint64_t voxels = 0;
  for (std::size_t i = 0; i < sky_.clouds.size(); ++i) {
    const volume::SkyCloud& sc = sky_.clouds[i];
    CloudSlot s;
    s.position_y = z_up_to_y_up(sc.position_m);
    if (!sc.file.empty()) {
      s.name = sc.file;
      s.path = sc.file;
      s.grid = sc.grid;
      s.up = static_cast<int>(parse_up_axis(sc.up));
      s.pattern = SequencePattern::parse(sc.file, "sky cloud file");  // checked again: a Sky may be built in code
      if (s.pattern.has_field) {
        s.frames = existing_sequence_frames(sc.file);
        if (!sequence_timed) {
          // The sequence's own clock: a keyframe per frame, at the fps of its first file.
          double fps = 24.0;
          s.file_grid = load_cloud_grid(s.pattern.path(s.frames.front()), sc.grid, static_cast<UpAxis>(s.up), &fps);  // kept for keyframe 0
          if (!(fps > 0.0 && fps <= 1000.0)) fps = 24.0;
          interval_s_ = 1.0 / fps;
          sequence_timed = true;
        }
      } else {
        require_cloud_file(sc.file);
      }
    } else {
      s.name = sc.preset + " #" + std::to_string(i);
      s.params = volume::sky_cloud_params(sky_, i);
      const volume::Aabb b = volume::CloudModel(s.params, sky_.voxel_size_m, 0.0).bounds();
      if (b.empty()) throw std::invalid_argument("sky clouds[" + std::to_string(i) + "]: the cloud has no extent");
      const glm::dvec3 n = (b.hi - b.lo) / sky_.voxel_size_m + 3.0;
      voxels += static_cast<uint64_t>(n.x) * static_cast<uint64_t>(n.y) * static_cast<uint64_t>(n.z);
    }
    slots_.push_back(std::move(s));
  }
  // Held at once, at worst: kKeep keyframes of every preset's bounds, plus a pair's two copies.
  ensure_fits_in_memory(voxels * (kKeep + 2), sizeof(float), "the sky's keyframes");
}

SkyKeyframes::~SkyKeyframes() = default;

int64_t SkyKeyframes::keyframe_at(double t) const {
  return static_cast<int64_t>(std::floor(t / interval_s_));
}

double SkyKeyframes::blend_at(double t) const {
  const double x = t / interval_s_;
  const double w = x - std::floor(x);
  return w < 1.0 ? w : 0.0;  // rounding can give exactly 1 for tiny negative x
}

void SkyKeyframes::request(int64_t k, int direction) {
  // Held: the kKeep nearest the pair drawn (its later keyframe going forward, its first going back).
  const bool forward = direction >= 0;
  worker_.want({}, {k, k + 1, forward ? k + 2 : k - 1, forward ? k + 3 : k - 2}, 2 * (k + (forward ? 1 : 0)), kKeep);
}

bool SkyKeyframes::ready(int64_t k) const { return worker_.get({}, k) != nullptr; }

void SkyKeyframes::wait(int64_t k) { worker_.wait({}, k); }

std::string SkyKeyframes::error() const { return worker_.error(); }

SkyKeyframes::Keyframe SkyKeyframes::make(int64_t k) const {
  Keyframe grids;
  volume::GenerateOptions opt;
  opt.voxel_size = sky_.voxel_size_m;
  opt.time = static_cast<double>(k) * interval_s_;
  for (const CloudSlot& s : slots_) {
    if (worker_.stopping()) throw std::runtime_error("stopped");
    if (s.path.empty()) {
      opt.reuse = &s.reuse;  // the sky's clouds do not drift in the model: the far tests carry over
      opt.y_up = true;
      grids.push_back(volume::generate_density(s.params, opt));
    } else if (s.frames.empty()) {
      if (!s.file_grid) s.file_grid = load_cloud_grid(s.path, s.grid, static_cast<UpAxis>(s.up));
      grids.push_back(s.file_grid);
    } else {
      // Frame k of the sequence, looping.
      const int64_t count = static_cast<int64_t>(s.frames.size());
      const int frame = s.frames[static_cast<std::size_t>(((k % count) + count) % count)];
      if (frame == s.frames.front() && s.file_grid) {
        grids.push_back(s.file_grid);
        continue;
      }
      grids.push_back(load_cloud_grid(s.pattern.path(frame), s.grid, static_cast<UpAxis>(s.up)));
    }
  }
  return grids;
}

std::vector<CloudVolume> SkyKeyframes::pair(int64_t k) const {
  const std::shared_ptr<const Keyframe> a = worker_.get({}, k), b = worker_.get({}, k + 1);
  if (!a || !b)
    throw std::logic_error("sky keyframes " + std::to_string(k) + " and " + std::to_string(k + 1) + " are not both made");
  std::vector<CloudVolume> clouds;
  for (std::size_t i = 0; i < slots_.size(); ++i) {
    const openvdb::FloatGrid& ga = *(*a)[i];
    const openvdb::FloatGrid& gb = *(*b)[i];
    if (ga.transform() != gb.transform())
      throw std::runtime_error("sky cloud '" + slots_[i].name + "': keyframes " + std::to_string(k) + " and " +
                               std::to_string(k + 1) + " have different transforms (voxel size or placement)");
    // Both keyframes on the union of their active boxes; a cloud that has dissolved in both
    // keeps one empty voxel, which draws nothing.
    openvdb::CoordBBox box = ga.evalActiveVoxelBoundingBox();
    box.expand(gb.evalActiveVoxelBoundingBox());
    if (box.empty()) box = openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(0));
    openvdb::math::Transform::Ptr t = ga.transform().copy();
    t->postTranslate(openvdb::Vec3d(slots_[i].position_y.x, slots_[i].position_y.y, slots_[i].position_y.z));
    CloudVolume c = make_cloud_volume(volume::dense_box(ga, box), *t, optics_, slots_[i].name);
    set_next_keyframe(c, volume::dense_box(gb, box), 0.0);
    c.period_m = render_period(slots_[i].params);
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
