// CPU geometry of the half-angle slicer (Kniss et al. 2003): the slicing axis and compositing
// order, a convex bound of each cloud's non-zero density, the slice planes across the clouds,
// each plane's polygon inside a bound, and the light buffer's orthographic frame. Private to
// render/clouds/src/cloud_*.cpp.
#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "nimbus/render/core/cloud_slice_settings.hpp"
#include "nimbus/render/core/cloud_volume.hpp"

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

// A convex polytope, the intersection of half-spaces dot(n, x) <= d (world metres, n unit).
struct ConvexHull {
  std::vector<glm::dvec4> planes;  // (n, d)
  glm::dvec3 centre{0.0};          // a point inside, and the radius of a ball around it that
  double radius_m = 0.0;           // holds the hull
  bool empty = false;              // no point has non-zero density
};

// Where a cloud's trilinear density can be non-zero: its support box (index origin - 1 to
// origin + size) cut by the 26-DOP (13 directions of the index lattice: axes, face and body
// diagonals) of the supports (centre +- 1 voxel) of its voxels with density > 0 (in either
// keyframe when the cloud has a next one).
ConvexHull cloud_hull(const CloudVolume& cloud);

// The hull moved by offset_m.
ConvexHull translated(const ConvexHull& hull, const glm::dvec3& offset_m);

// Every face moved out by margin_m metres.
ConvexHull grown(const ConvexHull& hull, double margin_m);

// The convex polygon where the plane dot(n, x) = c cuts the hull, in order around it. Empty
// when the plane misses it.
std::vector<glm::dvec3> plane_hull_polygon(const ConvexHull& hull, const glm::dvec3& n, double c);

// The hull's vertices (those of its faces' polygons).
std::vector<glm::dvec3> hull_vertices(const ConvexHull& hull);

// Slice planes dot(axis, x) = first_m + k * spacing_m, k = 0 .. count - 1: count planes evenly
// across the extent of `points` along the axis, each at the middle of its slab.
struct SlicePlanes {
  double first_m = 0.0, spacing_m = 0.0;
  int count = 0;
};
SlicePlanes slice_planes(const std::vector<glm::dvec3>& points, const glm::dvec3& axis, int count);

// Every (slice, hull) polygon fanned into triangles, in drawing order: slice-major, then hull.
struct SliceMesh {
  std::vector<glm::vec3> vertices;  // world, metres
  // first vertex and vertex count of slice k, hull j at index k * hulls + j (count 0: none)
  std::vector<int> first, count;
};
SliceMesh build_slice_mesh(const std::vector<ConvexHull>& hulls, const glm::dvec3& axis, const SlicePlanes& planes);

// The light buffer's orthographic frame: a plane perpendicular to the light's propagation
// direction l over the footprint of `points`, with a margin of `margin_texels` texels each side.
struct LightFrame {
  glm::dvec3 u_axis{1, 0, 0}, w_axis{0, 1, 0};  // unit, perpendicular to l and each other
  double u0 = 0, w0 = 0;                        // footprint corner, metres along the axes
  double u_extent = 1, w_extent = 1;            // metres
  glm::dmat4 world_to_uv{1.0};                  // world -> (u, w) in [0, 1], z = 0, w = 1
  glm::dmat4 world_to_clip{1.0};                // world -> (2u - 1, 2w - 1, 0, 1)
  glm::dvec2 texel_m{1.0};                      // texel size along u and w, metres
};
LightFrame light_frame(const std::vector<glm::dvec3>& points, const glm::dvec3& l, int resolution,
                       double margin_texels = 2.0);

// The light buffer's perspective frame for a lamp at `lamp` (Kniss et al. 2003 for local lights):
// a pinhole looking along unit `forward`, its image plane (at distance 1) covering the
// projections of the `points` in front of the lamp, with `margin_texels` texels each side, and no
// wider than max_tan either way (about 76 degrees for 4). A texel is a ray from the lamp.
struct LampFrame {
  glm::dvec3 u_axis{1, 0, 0}, w_axis{0, 1, 0}, forward{0, 0, 1};  // unit, right-handed
  glm::dmat4 world_to_clip{1.0};  // clip = (2 tu' - 1, 2 tw' - 1, 0, 1) z, z = dot(x - lamp, forward)
  glm::dvec2 texel_tan{1.0};      // a texel's width on the image plane (tangent units)
  bool clipped = false;           // a point lay behind the lamp or beyond max_tan: it reads no shadow there
};
LampFrame lamp_frame(const std::vector<glm::dvec3>& points, const glm::dvec3& lamp, const glm::dvec3& forward,
                     int resolution, double margin_texels = 2.0, double max_tan = 4.0);

}  // namespace nimbus::render::cloud_detail
