// The exact CPU reference of the light-shaft scene: one ray per pixel centre, analytic
// ray-scene intersection, lit intervals found by shadow rays and bisection, and adaptive
// Gauss-Kronrod quadrature of the single-scattered airlight, all in double precision.
#pragma once
#include <functional>

#include <glm/glm.hpp>

#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/core/image.hpp"
#include "nimbus/render/scene/scene.hpp"

namespace nimbus::render {

struct ReferenceSettings {
  double rel_tol = 1e-4;  // relative tolerance of each light's airlight integral, in (0, 0.1]
  int threads = 0;        // 0 = all cores (TBB's default)
  // N: the sample grid along each view ray on which visibility changes are looked for
  // (reference_visibility.hpp). For a point light N + 1 points evenly in the angle seen from
  // the light (a shadow feature narrower than about pi / N radians as seen from the light can
  // be missed) and N / 4 + 1 evenly in distance; for the sun N + 1 evenly over the part of the
  // ray whose sun rays can meet an occluder. Only the points inside some occluder's shadow
  // region are traced.
  int visibility_samples = 1024;
  // Surfaces add the airlight they reflect from each point light (Sun et al. eq. 13's L_p,a),
  // from SurfaceAirlightTable in double (core/surface_airlight.hpp): the same term as the GPU's
  // ShaftSettings::surface_airlight, bilinear in the same table, error as in docs/shafts.md.
  bool surface_airlight = true;
  std::function<void(double)> progress;  // fraction of rows done, in [0, 1]; may be empty
};

// Throws std::invalid_argument naming the field.
void validate(const ReferenceSettings& settings);

// Renders `scene` (validated; std::invalid_argument naming the field) through `camera`
// (validated): RGB = radiance (W sr^-1 m^-2), premultiplied by alpha; alpha = 1 where a
// surface or bulb is hit, else 1 - e^(-sigma_t inf) (1 in fog, 0 in vacuum). Metadata:
// describe_frame's (metadata.hpp) with method "reference", plus "rel_tol",
// "visibility_samples" and "surface_airlight".
// Throws std::runtime_error if a pixel came out NaN or infinite.
Image render_reference(const Scene& scene, const Camera& camera, const ReferenceSettings& settings = {});

// Radiance (RGB) and alpha of the single view ray from the camera's eye along unit `dir`;
// what render_reference computes for each pixel centre.
struct ReferenceSample {
  glm::dvec3 radiance{0.0};
  double alpha = 0.0;
};
ReferenceSample reference_ray(const Scene& scene, const glm::dvec3& eye, const glm::dvec3& dir,
                              const ReferenceSettings& settings = {});

}  // namespace nimbus::render
