// The exact image of the cloud model with multiple scattering: a CPU volumetric path tracer.
// Free flights by delta tracking (Woodcock et al. 1965) and shadow transmittance by ratio tracking
// (Novák et al. 2014) against majorants per 8^3 brick of each cloud's voxels (the size of an
// OpenVDB leaf node), met by a 3D DDA (Amanatides & Woo 1987), so empty bricks cost a step and no
// density lookups. The clouds' own dual-lobe Henyey-Greenstein phase, grey extinction and
// chromatic albedo (as a path weight); the sun by next-event estimation, the sky (scene.hpp Sky)
// where a scattered path escapes. Double-precision accumulation, one RNG stream per pixel
// (deterministic per seed, whatever the threads do), and per-pixel variance, so every image
// states its own noise. With max_bounces = 1 it computes what render_cloud_reference does.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/cloud_volume.hpp"
#include "nimbus/render/core/image.hpp"
#include "nimbus/render/scene/scene.hpp"

namespace nimbus::render {

struct PathTracerSettings {
  int samples_per_pixel = 64;     // [1, 1 << 20]
  int max_bounces = 1000;         // scattering events per path, [1, 100000]; high enough not to matter
  int roulette_after = 16;        // Russian roulette from this bounce on (unbiased), >= 1
  uint64_t seed = 1;
  int threads = 0;                // 0 = all cores
  std::optional<Sky> sky;         // lights the clouds where scattered paths escape; none: black
  bool sky_background = false;    // camera rays that escape see the sky (else transparent black)
  std::function<void(double)> progress;  // fraction of rows done; may be empty
};

void validate(const PathTracerSettings& settings);

struct PathTracedImage {
  Image image;                    // RGB radiance (premultiplied, over transparent black unless
                                  // sky_background), alpha = 1 - mean view transmittance
  std::vector<float> std_error;   // per pixel, per RGB channel: standard error of the mean
  double mean_relative_error = 0; // mean over covered pixels (alpha > 0.01) of std error / mean (luminance)
  double seconds = 0;
};

// Throws std::invalid_argument naming the bad field; std::runtime_error when a pixel came out NaN
// or infinite. Metadata: method "cloud-path-tracer", samples, bounces, seed, noise, camera, light.
PathTracedImage render_cloud_path_traced(const std::vector<CloudVolume>& clouds, const Camera& camera,
                                         const Light& light, const PathTracerSettings& settings = {});

// Where a photon ends: the building block of the image above, exposed for the transport tests.
// A walk starts at `origin` travelling along unit `dir` with weight 1 (per channel); each real
// collision scatters it (weight times albedo) until it leaves every cloud or the bounce limit.
struct PhotonExit {
  bool escaped = false;           // left every cloud (else absorbed by roulette or the limit)
  glm::dvec3 position{0.0}, direction{0.0};
  glm::dvec3 weight{1.0};
  int bounces = 0;
};
// The clouds' brick majorants are built once, for any number of photons; `clouds` must outlive it.
class PhotonTracer {
 public:
  explicit PhotonTracer(const std::vector<CloudVolume>& clouds);  // std::invalid_argument for a bad cloud
  ~PhotonTracer();
  PhotonTracer(const PhotonTracer&) = delete;
  PhotonTracer& operator=(const PhotonTracer&) = delete;
  PhotonExit trace(const glm::dvec3& origin, const glm::dvec3& dir, uint64_t seed, uint64_t stream,
                   int max_bounces = 100000, int roulette_after = 1 << 30) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace nimbus::render
