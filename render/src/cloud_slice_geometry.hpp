// CPU geometry of the half-angle slicer (Kniss et al. 2003): the slicing axis and compositing
// order, the slice planes across the clouds, each plane's polygon inside a cloud's support box,
// and the light buffer's orthographic frame. Private to render/src/cloud_*.cpp.
#pragma once
#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "nimbus/render/cloud_renderer.hpp"

namespace nimbus::render::cloud_detail {

// The slicing axis s and the eye's compositing order. Slices are drawn in increasing s.x,
// which is the light's propagation order (dot(s, l) > 0) in both branches.
struct SliceAxis {
  glm::dvec3 axis{0.0, 0.0, 1.0};  // s, unit
  bool front_to_back = true;       // eye composites "under" (s = v + l), else "over" (s = l - v)
  double half_angle_rad = 0.0;     // between s and the view line (v or -v), [0, pi/2]
};

// v: unit camera forward; l: unit light propagation direction. Auto chooses by sign(dot(v, l));
// a forced branch whose half vector vanishes (v = -l for FrontToBack, v = l for BackToFront)
// falls back to s = l.
SliceAxis choose_slice_axis(const glm::dvec3& v, const glm::dvec3& l, CloudSliceSettings::Branch branch);

// The 8 corners (world, metres) of a cloud's support: index origin - 1 to origin + size on each
// axis through index_to_world (an oriented box; corner bit a set = the high end of axis a),
// each face moved out by margin_m metres.
std::array<glm::dvec3, 8> support_corners(const CloudVolume& cloud, double margin_m = 0.0);

// The convex polygon where the plane dot(n, x) = c cuts the box of `corners`, its vertices in
// order around it (angle about their centroid). Empty when the plane misses the box or touches
// it in fewer than 3 points.
std::vector<glm::dvec3> plane_box_polygon(const std::array<glm::dvec3, 8>& corners, const glm::dvec3& n, double c);

// Slice planes dot(axis, x) = first_m + k * spacing_m, k = 0 .. count - 1: count planes evenly
// across [lo, hi] (the union support's extent along the axis), each at the middle of its slab.
struct SlicePlanes {
  double first_m = 0.0, spacing_m = 0.0;
  int count = 0;
};
SlicePlanes slice_planes(const std::vector<std::array<glm::dvec3, 8>>& boxes, const glm::dvec3& axis, int count);

// Every (slice, cloud) polygon fanned into triangles, in drawing order: slice-major, then cloud.
struct SliceMesh {
  std::vector<glm::vec3> vertices;  // world, metres
  // first vertex and vertex count of slice k, cloud j at index k * clouds + j (count 0: none)
  std::vector<int> first, count;
};
SliceMesh build_slice_mesh(const std::vector<std::array<glm::dvec3, 8>>& boxes, const glm::dvec3& axis,
                           const SlicePlanes& planes);

// The light buffer's orthographic frame: a plane perpendicular to the light's propagation
// direction l over the clouds' footprint, with a margin of `margin_texels` texels each side.
struct LightFrame {
  glm::dvec3 u_axis{1, 0, 0}, w_axis{0, 1, 0};  // unit, perpendicular to l and each other
  double u0 = 0, w0 = 0;                        // footprint corner, metres along the axes
  double u_extent = 1, w_extent = 1;            // metres
  glm::dmat4 world_to_uv{1.0};                  // world -> (u, w) in [0, 1], z = 0, w = 1
  glm::dmat4 world_to_clip{1.0};                // world -> (2u - 1, 2w - 1, 0, 1)
  glm::dvec2 texel_m{1.0};                      // texel size along u and w, metres
};
LightFrame light_frame(const std::vector<std::array<glm::dvec3, 8>>& boxes, const glm::dvec3& l, int resolution,
                       double margin_texels = 2.0);

}  // namespace nimbus::render::cloud_detail
