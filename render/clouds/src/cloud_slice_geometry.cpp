// CPU geometry of the half-angle slicer (cloud_slice_geometry.hpp): axis, convex bounds, planes,
// plane-bound polygons and the light buffer's frame.
#include "cloud_slice_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace nimbus::render::cloud_detail {

SliceAxis choose_slice_axis(const glm::dvec3& v, const glm::dvec3& l, CloudSliceSettings::Branch branch) {
  using Branch = CloudSliceSettings::Branch;
  SliceAxis a;
  // Kniss et al. 2003: the half vector of the view and the light's propagation direction, the
  // view term flipped when they are more than 90 degrees apart.
  a.front_to_back = branch == Branch::Auto ? glm::dot(v, l) >= 0.0 : branch == Branch::FrontToBack;
  const glm::dvec3 h = a.front_to_back ? v + l : l - v;
  const double len = glm::length(h);
  a.axis = len > 1e-9 ? h / len : l;
  // A forced branch far on the wrong side of the switch leaves s almost perpendicular to the
  // light, where the light's slab d / dot(l, s) blows up: slice along the light instead.
  if (!(glm::dot(a.axis, l) > 1e-3)) a.axis = l;
  a.half_angle_rad = std::acos(std::min(1.0, std::abs(glm::dot(a.axis, v))));
  return a;
}

namespace {

// Keeps the part of the convex polygon `poly` where dot(n, x) <= d (Sutherland & Hodgman 1974).
std::vector<glm::dvec3> clip(const std::vector<glm::dvec3>& poly, const glm::dvec3& n, double d) {
  std::vector<glm::dvec3> out;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const glm::dvec3& a = poly[i];
    const glm::dvec3& b = poly[(i + 1) % poly.size()];
    const double fa = glm::dot(n, a) - d, fb = glm::dot(n, b) - d;
    if (fa <= 0.0) out.push_back(a);
    if ((fa <= 0.0) != (fb <= 0.0)) out.push_back(a + (b - a) * (fa / (fa - fb)));
  }
  return out;
}

// The plane dot(n, x) = c cut by every plane of the hull but number `skip`.
std::vector<glm::dvec3> cut(const ConvexHull& hull, const glm::dvec3& n, double c, std::size_t skip) {
  if (hull.empty) return {};
  const double off = glm::dot(n, hull.centre) - c;
  if (std::abs(off) >= hull.radius_m) return {};
  // A square on the plane around the ball's cross-section, then clipped.
  const glm::dvec3 p0 = hull.centre - off * n;
  const glm::dvec3 helper = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 e1 = glm::normalize(glm::cross(n, helper)) * (2.0 * hull.radius_m);
  const glm::dvec3 e2 = glm::normalize(glm::cross(n, e1)) * (2.0 * hull.radius_m);
  std::vector<glm::dvec3> poly = {p0 - e1 - e2, p0 + e1 - e2, p0 + e1 + e2, p0 - e1 + e2};
  for (std::size_t i = 0; i < hull.planes.size() && poly.size() >= 3; ++i)
    if (i != skip) poly = clip(poly, glm::dvec3(hull.planes[i]), hull.planes[i].w);
  if (poly.size() < 3) return {};
  return poly;
}

}  // namespace

ConvexHull cloud_hull(const CloudVolume& cloud) {
  // The 13 directions of a 26-DOP in index space.
  static const int kDir[13][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1},  {1, 1, 0},  {1, -1, 0}, {1, 0, 1}, {1, 0, -1},
                                  {0, 1, 1}, {0, 1, -1}, {1, 1, 1}, {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};
  double lo[13], hi[13];
  for (int i = 0; i < 13; ++i) {
    lo[i] = std::numeric_limits<double>::max();
    hi[i] = -lo[i];
  }
  const volume::DenseBox& b = cloud.box;
  // With a next keyframe, the union of both supports: the hull holds the blend at any weight.
  const bool next = !cloud.next_box.values.empty();
  bool any = false;
  std::size_t n = 0;
  for (int64_t k = 0; k < b.size[2]; ++k)
    for (int64_t j = 0; j < b.size[1]; ++j)
      for (int64_t i = 0; i < b.size[0]; ++i, ++n) {
        if (!(b.values[n] > 0.0f) && !(next && cloud.next_box.values[n] > 0.0f)) continue;
        any = true;
        const double c[3] = {static_cast<double>(b.origin[0] + i), static_cast<double>(b.origin[1] + j),
                             static_cast<double>(b.origin[2] + k)};
        for (int d = 0; d < 13; ++d) {
          const double v = kDir[d][0] * c[0] + kDir[d][1] * c[1] + kDir[d][2] * c[2];
          lo[d] = std::min(lo[d], v);
          hi[d] = std::max(hi[d], v);
        }
      }
  ConvexHull h;
  if (!any) {
    h.empty = true;
    return h;
  }
  // Index-space dot(m, idx) <= e with idx = L x + t (world_to_index) is dot(L^T m, x) <= e - dot(m, t).
  const glm::dmat4& w = cloud.world_to_index;
  const glm::dvec3 t(w[3]);
  for (int d = 0; d < 13; ++d) {
    const glm::dvec3 m(kDir[d][0], kDir[d][1], kDir[d][2]);
    const double reach = std::abs(m.x) + std::abs(m.y) + std::abs(m.z);  // a voxel's support, centre +- 1
    for (int sign : {1, -1}) {
      const glm::dvec3 ms = static_cast<double>(sign) * m;
      const double e = sign > 0 ? hi[d] + reach : -(lo[d] - reach);
      const glm::dvec3 g(glm::dot(glm::dvec3(w[0]), ms), glm::dot(glm::dvec3(w[1]), ms), glm::dot(glm::dvec3(w[2]), ms));
      const double len = glm::length(g);
      h.planes.emplace_back(g / len, (e - glm::dot(ms, t)) / len);
    }
  }
  // The ball around the axis-aligned index box of the DOP.
  glm::dvec3 corner_lo, corner_hi;
  for (int a = 0; a < 3; ++a) {
    corner_lo[a] = lo[a] - 1.0;
    corner_hi[a] = hi[a] + 1.0;
  }
  h.centre = glm::dvec3(cloud.index_to_world * glm::dvec4(0.5 * (corner_lo + corner_hi), 1.0));
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 idx((c & 1) ? corner_hi.x : corner_lo.x, (c & 2) ? corner_hi.y : corner_lo.y,
                         (c & 4) ? corner_hi.z : corner_lo.z);
    h.radius_m = std::max(h.radius_m, glm::length(glm::dvec3(cloud.index_to_world * glm::dvec4(idx, 1.0)) - h.centre));
  }
  h.radius_m *= 1.0 + 1e-9;
  return h;
}

ConvexHull translated(const ConvexHull& hull, const glm::dvec3& offset_m) {
  ConvexHull h = hull;
  // dot(n, x) <= d for x in the hull is dot(n, x + o) <= d + dot(n, o) for the moved points.
  for (glm::dvec4& p : h.planes) p.w += glm::dot(glm::dvec3(p), offset_m);
  h.centre += offset_m;
  return h;
}

ConvexHull grown(const ConvexHull& hull, double margin_m) {
  ConvexHull g = hull;
  for (glm::dvec4& p : g.planes) p.w += margin_m;
  g.radius_m += margin_m;
  return g;
}

std::vector<glm::dvec3> plane_hull_polygon(const ConvexHull& hull, const glm::dvec3& n, double c) {
  return cut(hull, n, c, hull.planes.size());
}

std::vector<glm::dvec3> hull_vertices(const ConvexHull& hull) {
  std::vector<glm::dvec3> out;
  for (std::size_t i = 0; i < hull.planes.size(); ++i) {
    const std::vector<glm::dvec3> face = cut(hull, glm::dvec3(hull.planes[i]), hull.planes[i].w, i);
    out.insert(out.end(), face.begin(), face.end());
  }
  return out;
}

SlicePlanes slice_planes(const std::vector<glm::dvec3>& points, const glm::dvec3& axis, int count) {
  double lo = std::numeric_limits<double>::max(), hi = -lo;
  for (const glm::dvec3& p : points) {
    lo = std::min(lo, glm::dot(axis, p));
    hi = std::max(hi, glm::dot(axis, p));
  }
  if (!(hi > lo)) {  // nothing to slice: any planes (no polygon will be found)
    lo = 0.0;
    hi = 1.0;
  }
  SlicePlanes s;
  s.count = count;
  s.spacing_m = (hi - lo) / count;
  s.first_m = lo + 0.5 * s.spacing_m;
  return s;
}

SliceMesh build_slice_mesh(const std::vector<ConvexHull>& hulls, const glm::dvec3& axis, const SlicePlanes& planes) {
  SliceMesh m;
  const std::size_t n = static_cast<std::size_t>(planes.count) * hulls.size();
  m.first.assign(n, 0);
  m.count.assign(n, 0);
  for (int k = 0; k < planes.count; ++k) {
    const double c = planes.first_m + k * planes.spacing_m;
    for (std::size_t j = 0; j < hulls.size(); ++j) {
      const std::size_t idx = static_cast<std::size_t>(k) * hulls.size() + j;
      const std::vector<glm::dvec3> poly = plane_hull_polygon(hulls[j], axis, c);
      m.first[idx] = static_cast<int>(m.vertices.size());
      for (std::size_t i = 1; i + 1 < poly.size(); ++i) {  // a fan
        m.vertices.emplace_back(poly[0]);
        m.vertices.emplace_back(poly[i]);
        m.vertices.emplace_back(poly[i + 1]);
      }
      m.count[idx] = static_cast<int>(m.vertices.size()) - m.first[idx];
    }
  }
  return m;
}

LightFrame light_frame(const std::vector<glm::dvec3>& points, const glm::dvec3& l, int resolution,
                       double margin_texels) {
  LightFrame f;
  const glm::dvec3 helper = std::abs(l.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  f.u_axis = glm::normalize(glm::cross(helper, l));
  f.w_axis = glm::cross(l, f.u_axis);
  double lo[2] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  double hi[2] = {-lo[0], -lo[1]};
  for (const glm::dvec3& p : points) {
    const double c[2] = {glm::dot(f.u_axis, p), glm::dot(f.w_axis, p)};
    for (int a = 0; a < 2; ++a) {
      lo[a] = std::min(lo[a], c[a]);
      hi[a] = std::max(hi[a], c[a]);
    }
  }
  for (int a = 0; a < 2; ++a)
    if (!(hi[a] >= lo[a])) lo[a] = hi[a] = 0.0;
  double origin[2], extent[2];
  for (int a = 0; a < 2; ++a) {
    const double texel = std::max(hi[a] - lo[a], 1e-9) / (resolution - 2.0 * margin_texels);
    origin[a] = lo[a] - margin_texels * texel;
    extent[a] = texel * resolution;
    f.texel_m[a] = texel;
  }
  f.u0 = origin[0];
  f.w0 = origin[1];
  f.u_extent = extent[0];
  f.w_extent = extent[1];
  glm::dmat4 uv(0.0), clip(0.0);
  const glm::dvec3 axes[2] = {f.u_axis, f.w_axis};
  for (int a = 0; a < 2; ++a) {
    for (int c = 0; c < 3; ++c) {
      uv[c][a] = axes[a][c] / extent[a];
      clip[c][a] = 2.0 * axes[a][c] / extent[a];
    }
    uv[3][a] = -origin[a] / extent[a];
    clip[3][a] = -2.0 * origin[a] / extent[a] - 1.0;
  }
  uv[3][3] = 1.0;
  clip[3][3] = 1.0;
  f.world_to_uv = uv;
  f.world_to_clip = clip;
  return f;
}

LampFrame lamp_frame(const std::vector<glm::dvec3>& points, const glm::dvec3& lamp, const glm::dvec3& forward,
                     int resolution, double margin_texels, double max_tan) {
  LampFrame f;
  f.forward = glm::normalize(forward);
  const glm::dvec3 helper = std::abs(f.forward.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  f.u_axis = glm::normalize(glm::cross(helper, f.forward));
  f.w_axis = glm::cross(f.forward, f.u_axis);
  double lo[2] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  double hi[2] = {-lo[0], -lo[1]};
  for (const glm::dvec3& p : points) {
    const glm::dvec3 d = p - lamp;
    const double z = glm::dot(d, f.forward);
    if (!(z > 1e-9 * (1.0 + glm::length(d)))) {
      f.clipped = true;
      continue;
    }
    const double t[2] = {glm::dot(d, f.u_axis) / z, glm::dot(d, f.w_axis) / z};
    for (int a = 0; a < 2; ++a) {
      if (std::abs(t[a]) > max_tan) f.clipped = true;
      lo[a] = std::min(lo[a], std::clamp(t[a], -max_tan, max_tan));
      hi[a] = std::max(hi[a], std::clamp(t[a], -max_tan, max_tan));
    }
  }
  double origin[2], extent[2];
  for (int a = 0; a < 2; ++a) {
    if (!(hi[a] >= lo[a])) lo[a] = -1.0, hi[a] = 1.0;  // nothing in front: any frame
    const double texel = std::max(hi[a] - lo[a], 1e-9) / (resolution - 2.0 * margin_texels);
    origin[a] = lo[a] - margin_texels * texel;
    extent[a] = texel * resolution;
    f.texel_tan[a] = texel;
  }
  // Rows of the clip map in view coordinates (u, w, z): x_clip = (2 / e) u - (2 o / e + 1) z, the
  // same for y, z_clip = 0, w_clip = z; then world -> view.
  glm::dmat4 view(1.0);  // world -> (u, w, z), column-major
  const glm::dvec3 axes[3] = {f.u_axis, f.w_axis, f.forward};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) view[c][r] = axes[r][c];
    view[3][r] = -glm::dot(axes[r], lamp);
  }
  glm::dmat4 proj(0.0);
  for (int a = 0; a < 2; ++a) {
    proj[a][a] = 2.0 / extent[a];
    proj[2][a] = -(2.0 * origin[a] / extent[a] + 1.0);
  }
  proj[2][3] = 1.0;
  f.world_to_clip = proj * view;
  return f;
}

}  // namespace nimbus::render::cloud_detail
