// CPU geometry of the half-angle slicer (cloud_slice_geometry.hpp): axis, planes, box-plane
// polygons and the light buffer's frame.
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

std::array<glm::dvec3, 8> support_corners(const CloudVolume& cloud, double margin_m) {
  std::array<glm::dvec3, 8> out;
  double pad[3];  // the margin in index units along each axis: |grad index_a| per metre
  for (int a = 0; a < 3; ++a) {
    const glm::dmat4& m = cloud.world_to_index;
    pad[a] = margin_m * glm::length(glm::dvec3(m[0][a], m[1][a], m[2][a]));
  }
  for (int k = 0; k < 8; ++k) {
    glm::dvec3 idx;
    for (int a = 0; a < 3; ++a)
      idx[a] = ((k >> a) & 1) ? cloud.box.origin[a] + static_cast<double>(cloud.box.size[a]) + pad[a]
                              : cloud.box.origin[a] - 1.0 - pad[a];
    out[static_cast<std::size_t>(k)] = glm::dvec3(cloud.index_to_world * glm::dvec4(idx, 1.0));
  }
  return out;
}

std::vector<glm::dvec3> plane_box_polygon(const std::array<glm::dvec3, 8>& corners, const glm::dvec3& n, double c) {
  std::vector<glm::dvec3> pts;
  double f[8];
  for (int k = 0; k < 8; ++k) f[k] = glm::dot(n, corners[static_cast<std::size_t>(k)]) - c;
  // The 12 edges join corners that differ in one bit.
  for (int k = 0; k < 8; ++k) {
    for (int bit = 1; bit < 8; bit <<= 1) {
      const int m = k | bit;
      if (m == k) continue;
      if ((f[k] < 0.0) == (f[m] < 0.0)) continue;
      const double t = f[k] / (f[k] - f[m]);
      pts.push_back(corners[static_cast<std::size_t>(k)] +
                    t * (corners[static_cast<std::size_t>(m)] - corners[static_cast<std::size_t>(k)]));
    }
  }
  if (pts.size() < 3) return {};
  glm::dvec3 centre(0.0);
  for (const glm::dvec3& p : pts) centre += p;
  centre /= static_cast<double>(pts.size());
  const glm::dvec3 helper = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 e1 = glm::normalize(glm::cross(n, helper));
  const glm::dvec3 e2 = glm::cross(n, e1);
  std::sort(pts.begin(), pts.end(), [&](const glm::dvec3& a, const glm::dvec3& b) {
    return std::atan2(glm::dot(a - centre, e2), glm::dot(a - centre, e1)) <
           std::atan2(glm::dot(b - centre, e2), glm::dot(b - centre, e1));
  });
  return pts;
}

SlicePlanes slice_planes(const std::vector<std::array<glm::dvec3, 8>>& boxes, const glm::dvec3& axis, int count) {
  double lo = std::numeric_limits<double>::max(), hi = -lo;
  for (const auto& box : boxes)
    for (const glm::dvec3& p : box) {
      lo = std::min(lo, glm::dot(axis, p));
      hi = std::max(hi, glm::dot(axis, p));
    }
  SlicePlanes s;
  s.count = count;
  s.spacing_m = (hi - lo) / count;
  s.first_m = lo + 0.5 * s.spacing_m;
  return s;
}

SliceMesh build_slice_mesh(const std::vector<std::array<glm::dvec3, 8>>& boxes, const glm::dvec3& axis,
                           const SlicePlanes& planes) {
  SliceMesh m;
  const std::size_t n = static_cast<std::size_t>(planes.count) * boxes.size();
  m.first.assign(n, 0);
  m.count.assign(n, 0);
  for (int k = 0; k < planes.count; ++k) {
    const double c = planes.first_m + k * planes.spacing_m;
    for (std::size_t j = 0; j < boxes.size(); ++j) {
      const std::size_t idx = static_cast<std::size_t>(k) * boxes.size() + j;
      const std::vector<glm::dvec3> poly = plane_box_polygon(boxes[j], axis, c);
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

LightFrame light_frame(const std::vector<std::array<glm::dvec3, 8>>& boxes, const glm::dvec3& l, int resolution,
                       double margin_texels) {
  LightFrame f;
  const glm::dvec3 helper = std::abs(l.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  f.u_axis = glm::normalize(glm::cross(helper, l));
  f.w_axis = glm::cross(l, f.u_axis);
  double lo[2] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  double hi[2] = {-lo[0], -lo[1]};
  for (const auto& box : boxes)
    for (const glm::dvec3& p : box) {
      const double c[2] = {glm::dot(f.u_axis, p), glm::dot(f.w_axis, p)};
      for (int a = 0; a < 2; ++a) {
        lo[a] = std::min(lo[a], c[a]);
        hi[a] = std::max(hi[a], c[a]);
      }
    }
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

}  // namespace nimbus::render::cloud_detail
