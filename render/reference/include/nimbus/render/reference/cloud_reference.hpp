// The exact image of the cloud model on the CPU: single scattering of the sun or lamps
// (light.hpp; and the ambient sky term) by every cloud, one ray per pixel centre, fine
// midpoint steps in double precision with the energy-conserving step integral (Hillaire 2015),
// a shadow ray to every light at every step (to a lamp, it ends at the lamp). The half-angle
// slicer's error is measured against it; it is itself checked against OpenVDB's vdb_render.
#pragma once
#include <functional>
#include <vector>

#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/cloud_volume.hpp"
#include "nimbus/render/core/image.hpp"

namespace nimbus::render {

struct CloudReferenceSettings {
  double view_step_voxels = 0.25;    // primary step, in voxels of the finest cloud, (0, 8]
  double shadow_step_voxels = 0.5;   // step along the shadow ray, in voxels, (0, 8]
  double min_transmittance = 1e-6;   // a view ray stops when its transmittance falls below, [0, 0.1]
  int threads = 0;                   // 0 = all cores
  std::function<void(double)> progress;  // fraction of rows done; may be empty
};

void validate(const CloudReferenceSettings& settings);

// Clouds alone, over transparent black: RGB = radiance (W sr^-1 m^-2) already premultiplied
// (it is the in-scattered light), alpha = 1 - view transmittance through every cloud. Overlapping
// clouds add their extinction and scattering. Metadata: method "cloud-reference", the steps,
// camera and light. Throws std::invalid_argument naming the bad field, std::runtime_error if a
// pixel came out NaN or infinite.
Image render_cloud_reference(const std::vector<CloudVolume>& clouds, const Camera& camera, const Light& light,
                             const CloudReferenceSettings& settings = {});
// Several lights (at least one): their single scattering adds up.
Image render_cloud_reference(const std::vector<CloudVolume>& clouds, const Camera& camera,
                             const std::vector<Light>& lights, const CloudReferenceSettings& settings = {});

// One ray from `eye` along unit `dir`: what render_cloud_reference computes for a pixel centre.
struct CloudSample {
  glm::dvec3 radiance{0.0};
  double alpha = 0.0;
};
CloudSample cloud_reference_ray(const std::vector<CloudVolume>& clouds, const Light& light, const glm::dvec3& eye,
                                const glm::dvec3& dir, const CloudReferenceSettings& settings = {});
CloudSample cloud_reference_ray(const std::vector<CloudVolume>& clouds, const std::vector<Light>& lights,
                                const glm::dvec3& eye, const glm::dvec3& dir, const CloudReferenceSettings& settings = {});

// Transmittance from `point` towards the light through every cloud (the shadow ray alone; to a
// lamp it ends at the lamp).
double cloud_light_transmittance(const std::vector<CloudVolume>& clouds, const Light& light,
                                 const glm::dvec3& point_m, double shadow_step_voxels = 0.5);

}  // namespace nimbus::render
