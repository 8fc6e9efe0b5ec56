// Builds the light volume (nimbus/render/core/light_volume.hpp) on the CPU: photons from the sun
// through the clouds with the path tracer's own free flights (delta tracking against the 8^3
// brick majorants, cloud_path_tracer.hpp), their weights the product of the albedos met; from the
// first real collision on, each flight tallies its exact length in every cell it crosses inside
// the bricks (a 3D DDA), times its weight: the track-length estimate of the fluence of scattered
// light (Spanier & Gelbard 1969; eq. MS-2 in docs/clouds.md), and the same times the direction
// for the net flux, and times d d^T - I / 3 for the second moment. Deterministic per seed, whatever the
// threads: photon i draws from its own stream and the tallies are fixed-point integers, each
// thread's own, summed after. With settings.diffusion_depth > 0 a photon that scatters deep inside
// the clouds hands its light to a diffusion solve on the grid (light_volume_diffusion.hpp); with
// settings.similarity_depth > 0 it flies on there in the similar isotropic medium instead (fewer,
// longer flights). Photons go in the order of their launch points along a Z curve, for the cache;
// the sums do not change.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/cloud_volume.hpp"
#include "nimbus/render/core/light_volume.hpp"

namespace nimbus::render {

// The grid the volume gets for these clouds and settings: cube cells, `resolution` along the
// union box's longest axis, or finer where the photons allow (settings.photons_per_cell); at
// least 8 cells across a thin axis. std::invalid_argument for an empty list or bad settings.
LightVolume light_volume_grid(const std::vector<CloudVolume>& clouds, const LightVolumeSettings& settings);

// Bytes that building that grid takes (the tallies and the result), for a refusal before
// allocating.
std::size_t light_volume_bytes(const LightVolume& grid);

// The volume for `light`'s direction (its irradiance does not enter: the volume is per unit
// irradiance). Throws std::invalid_argument naming a bad cloud, light or setting, and
// std::length_error when the tallies would need more than 4 GiB.
LightVolume build_light_volume(const std::vector<CloudVolume>& clouds, const Light& light,
                               const LightVolumeSettings& settings);

// What a build needs of the clouds whatever the sun's direction: the grid, the clouds' media,
// the covered cells and (with diffusion or similarity depths) the cells' optics. The setup of a
// build is most of its fixed cost (0.15 s of a 0.25 s build of 2^16 photons on the default
// sky); a viewer whose sun is dragged over still clouds makes it once per cloud state and starts
// each new sun's build from it. Immutable once made; the clouds are held with it.
class LightVolumeSetup {
 public:
  // Throws as build_light_volume for bad clouds or settings.
  LightVolumeSetup(std::shared_ptr<const std::vector<CloudVolume>> clouds, const LightVolumeSettings& settings);
  ~LightVolumeSetup();
  LightVolumeSetup(const LightVolumeSetup&) = delete;
  LightVolumeSetup& operator=(const LightVolumeSetup&) = delete;

  const LightVolume& grid() const;  // the cells, without values
  // Whether a build under `settings` can start from this setup: the same grid and depths.
  bool fits(const LightVolumeSettings& settings) const;
  double seconds() const;  // making it took

 private:
  friend class LightVolumeBuild;
  struct Data;
  std::unique_ptr<Data> d_;
};

// The same volume built progressively: photons are traced a share at a time, and volume() after
// any share is the volume of the photons traced so far on the final grid (fewer photons: more
// photon noise, the same mean). After all settings.photons it is build_light_volume's, bit for
// bit: the same photons make the same integer tallies however they are split. For a viewer: a
// first volume from a few photons in a fraction of the time, refined while it is shown.
// `clouds` must outlive the build. The constructor throws as build_light_volume; trace() and
// volume() poll their calling thread's stop (cancel.hpp). A trace that ends part-way (stopped,
// or an exception) leaves its share half-tallied: the build then refuses more calls
// (std::logic_error), and a new one starts over.
class LightVolumeBuild {
 public:
  LightVolumeBuild(const std::vector<CloudVolume>& clouds, const Light& light, const LightVolumeSettings& settings);
  // From a setup made before (for the same clouds, under settings it fits(): std::invalid_argument
  // otherwise). The volume is the same, bit for bit, as one built from the clouds directly.
  LightVolumeBuild(std::shared_ptr<const LightVolumeSetup> setup, const Light& light, const LightVolumeSettings& settings);
  ~LightVolumeBuild();
  LightVolumeBuild(const LightVolumeBuild&) = delete;
  LightVolumeBuild& operator=(const LightVolumeBuild&) = delete;

  // Traces the next `photons` photons (those left, when fewer are); returns the photons traced
  // in all. std::invalid_argument for a count < 1.
  std::int64_t trace(std::int64_t photons);
  std::int64_t traced() const;
  std::int64_t photons() const;  // settings.photons: the whole build
  bool done() const { return traced() >= photons(); }
  // The volume of the photons traced so far (its `photons` says how many); build_seconds is the
  // time spent on this build so far, this call included (so it adds to the build's time).
  // std::logic_error before any photon.
  LightVolume volume();

 private:
  friend LightVolume build_light_volume(const std::vector<CloudVolume>&, const Light&, const LightVolumeSettings&);
  // `consume`: the tallies move into the volume, and the build is spent (build_light_volume's
  // last call).
  LightVolume make_volume(bool consume);
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace nimbus::render
