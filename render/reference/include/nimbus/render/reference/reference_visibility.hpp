// Lit intervals of a view ray for the CPU reference: where along the ray a light is visible.
// Each occluder can only shadow the part of the ray inside its shadow region (found exactly
// for its bounding box: a cone from a point light beyond the box's front faces, or a prism
// along the sun's direction); shadow rays are sampled densely only there, and each change of
// visibility between two samples is bisected to 1e-9 relative.
#pragma once
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "nimbus/render/scene/intersect.hpp"

namespace nimbus::render {

using Intervals = std::vector<std::pair<double, double>>;

// Points p whose segment to a point light L meets the box [lo, hi], as an intersection of
// half-spaces n . p + w <= 0 (the cone from L through the box's silhouette edges and the
// box side of its faces that face L); `everywhere` when L is inside the box.
struct ShadowRegion {
  bool everywhere = false;
  int count = 0;
  glm::dvec4 planes[16];  // xyz = n, w
};
ShadowRegion point_shadow_region(const glm::dvec3& light, const glm::dvec3& lo, const glm::dvec3& hi);

// Clips [x0, x1] of the ray o + x d to the region; false when nothing is left.
bool clip_to_region(const ShadowRegion& region, const glm::dvec3& o, const glm::dvec3& d, double& x0,
                    double& x1);

// Range of x for which the ray from o + x d toward the unit direction u meets the box
// [lo, hi] (Fourier-Motzkin elimination of the distance along u); false when empty.
bool sun_shadow_range(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& u, const glm::dvec3& lo,
                      const glm::dvec3& hi, double& xa, double& xb);

// Lit intervals of [0, x_end] on the ray o + x d (d unit) for a point light, with the shadow
// regions of the tracer's occluders for that light (regions[k] for occluder k). Samples: n
// evenly in the angle seen from the light over the whole ray and n / 4 evenly in x, of which
// those inside some occluder's region are traced.
Intervals point_light_lit_intervals(const SceneTracer& tracer, const std::vector<ShadowRegion>& regions,
                                    const glm::dvec3& light, const glm::dvec3& o, const glm::dvec3& d,
                                    double x_end, int n);

// Lit intervals of [0, x_end] for the sun (unit direction u toward it): n samples evenly over
// the part of the ray whose sun rays can meet an occluder.
Intervals sun_lit_intervals(const SceneTracer& tracer, const glm::dvec3& u, const glm::dvec3& o,
                            const glm::dvec3& d, double x_end, int n);

}  // namespace nimbus::render
