// A sky's clouds as keyframes of their evolution, made on a background thread so that a render
// loop never waits on them. Keyframe k holds every cloud's density grid (y-up) at evolution time
// k * interval: a preset generated at that time, a VDB file as it is, or frame k of a VDB
// sequence (then the interval is the sequence's 1 / fps, and it loops). A pair of keyframes is
// copied onto the union of their active boxes, so the two blend voxel for voxel
// (CloudVolume::next_box). The wind is not in the keyframes: it moves the density field as a
// whole (CloudModel: q = p - wind t), which is a translation of the cloud by wind * t (motion()).
// A preset's keyframes after the first read the block and far tests the first saved
// (volume::GenerationReuse: they do not depend on time without drift) and are made y-up directly.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <openvdb/openvdb.h>

#include "nimbus/base/sequence_pattern.hpp"
#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/cloud_volume.hpp"
#include "nimbus/render/sky/keyframe_worker.hpp"
#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/sky.hpp"

namespace nimbus::render {

// A sky's file clouds, checked before the work (the checks SkyKeyframes makes): every file is a
// regular file, every sequence (name.%04d.vdb) has a frame from 0 to 99999 that is one.
// std::runtime_error naming the file ("is a FIFO, not a VDB file", "no frame of the sequence").
void check_sky_cloud_files(const volume::Sky& sky);
// The frames of the sequence `file` that exist as regular files, ascending; the error above when none.
std::vector<int> existing_sequence_frames(const std::string& file);
// The error above unless `file` is a regular file.
void require_cloud_file(const std::string& file);

class SkyKeyframes {
 public:
  // Validates the sky (std::invalid_argument naming the key) and the optics, sizes every
  // preset's bounds (OutOfMemoryRequest when its keyframes could not be held), finds a
  // sequence's frames (std::runtime_error naming a file cloud with none) and starts the worker.
  // Nothing is generated or read until request() or wait().
  SkyKeyframes(volume::Sky sky, const CloudOptics& optics);
  ~SkyKeyframes();  // stops the worker (after the keyframe it is making)
  SkyKeyframes(const SkyKeyframes&) = delete;
  SkyKeyframes& operator=(const SkyKeyframes&) = delete;

  const volume::Sky& sky() const { return sky_; }
  double interval_s() const { return interval_s_; }
  // The keyframe at or before evolution time t, and the blend towards the next one, in [0, 1).
  int64_t keyframe_at(double evolution_time_s) const;
  double blend_at(double evolution_time_s) const;

  // Asks for keyframes k and k + 1, then k + 2 and k + 3 ahead in `direction` (+1 forward in
  // time, -1 backward); keyframes far from k are dropped. Never blocks.
  void request(int64_t k, int direction = 1);
  bool ready(int64_t k) const;
  // Blocks until keyframe k is made (requesting it first). Rethrows the worker's error.
  void wait(int64_t k);
  // The worker's error, if one stopped it (a message); empty otherwise.
  std::string error() const;

  // Every cloud with keyframe k as its density and keyframe k + 1 as its next (both must be
  // ready: std::logic_error otherwise), at its sky position, blend 0.
  std::vector<CloudVolume> pair(int64_t k) const;
  // Each cloud's drift at sky time t (wind * t; the wind z-up, as in the sky file) and the blend.
  std::vector<CloudMotion> motion(double sky_time_s, const glm::dvec3& wind_m_s, double blend) const;

  // Keyframes made, seconds generating them (the last: every cloud), and whether one is being made.
  KeyframeWorkerStats stats() const { return worker_.stats(); }

 private:
  struct CloudSlot {
    std::string name;
    glm::dvec3 position_y{0.0};          // the sky position, y-up
    volume::CloudParams params;          // a preset
    std::string path;                    // a file, or a sequence's pattern
    SequencePattern pattern;             // `path` parsed: the names of a sequence's frames
    std::string grid;
    int up = 0;                          // UpAxis
    std::vector<int> frames;             // a sequence's frame numbers, ascending; empty: one file
    // One file, read once (worker thread); for a sequence, its first frame, read for its fps.
    mutable openvdb::FloatGrid::ConstPtr file_grid;
    // A preset's tests that do not change from keyframe to keyframe (worker thread).
    mutable volume::GenerationReuse reuse;
  };
  using Keyframe = std::vector<openvdb::FloatGrid::ConstPtr>;
  Keyframe make(int64_t k) const;

  volume::Sky sky_;
  CloudOptics optics_;
  std::vector<CloudSlot> slots_;
  double interval_s_ = 1.0;
  // Last: its thread reads the members above. make() checks stopping() between clouds, so a
  // destructor waits one cloud at most.
  KeyframeWorker<Keyframe> worker_;
};

}  // namespace nimbus::render
