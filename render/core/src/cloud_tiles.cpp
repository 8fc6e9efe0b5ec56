// Which copies of periodic tiles the slicer draws, near and far (cloud_tiles.hpp).
#include "nimbus/render/core/cloud_tiles.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nimbus/base/validate.hpp"

namespace nimbus::render {
namespace {

// A rectangle in render x and z.
struct Rect {
  double x0 = 1e300, z0 = 1e300, x1 = -1e300, z1 = -1e300;
  void add(const glm::dvec3& lo, const glm::dvec3& hi) {
    x0 = std::min(x0, lo.x);
    z0 = std::min(z0, lo.z);
    x1 = std::max(x1, hi.x);
    z1 = std::max(z1, hi.z);
  }
  // Whether the box (shrunk by `margin` on x and z) reaches into the rectangle.
  bool overlaps(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec2& margin) const {
    return lo.x + margin.x < x1 && hi.x - margin.x > x0 && lo.z + margin.y < z1 && hi.z - margin.y > z0;
  }
};

bool periodic(const CloudVolume& c) { return c.period_m.x > 0.0 || c.period_m.z > 0.0; }

// A voxel's extent along render x and z: the index axes' world lengths, largest on each.
glm::dvec2 voxel_xz(const CloudVolume& c) {
  glm::dvec2 v(0.0);
  for (int a = 0; a < 3; ++a) {
    v.x = std::max(v.x, std::abs(c.index_to_world[a].x));
    v.y = std::max(v.y, std::abs(c.index_to_world[a].z));
  }
  return v;
}

// The eye's copy: the whole number of periods that brings the tile's centre nearest the eye.
glm::dvec3 eye_offset(const CloudVolume& c, const glm::dvec3& eye) {
  const glm::dvec3 centre = 0.5 * (c.world_min + c.world_max);
  glm::dvec3 o(0.0);
  if (c.period_m.x > 0.0) o.x = c.period_m.x * std::round((eye.x - centre.x) / c.period_m.x);
  if (c.period_m.z > 0.0) o.z = c.period_m.z * std::round((eye.z - centre.z) / c.period_m.z);
  return o;
}

// Distance in x and z from the eye to a box.
double xz_distance(const glm::dvec3& eye, const glm::dvec3& lo, const glm::dvec3& hi) {
  const double dx = std::max({lo.x - eye.x, 0.0, eye.x - hi.x});
  const double dz = std::max({lo.z - eye.z, 0.0, eye.z - hi.z});
  return std::hypot(dx, dz);
}

// Whether a box lies wholly outside one of the frustum's side planes or behind its near plane
// (tested on the homogeneous clip coordinates of its corners: each is a half-space in the world).
bool outside_frustum(const glm::dmat4& view_proj, const glm::dvec3& lo, const glm::dvec3& hi) {
  int out[5] = {0, 0, 0, 0, 0};
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 p((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
    const glm::dvec4 q = view_proj * glm::dvec4(p, 1.0);
    out[0] += q.x < -q.w;
    out[1] += q.x > q.w;
    out[2] += q.y < -q.w;
    out[3] += q.y > q.w;
    out[4] += q.z < -q.w;
  }
  return std::any_of(std::begin(out), std::end(out), [](int n) { return n == 8; });
}

}  // namespace

std::string period_fault(const CloudVolume& c) {
  const glm::dvec3& p = c.period_m;
  if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) return "must be finite";
  if (p.y != 0.0) return "repeats along render x and z only (the world's x and y); its y must be 0";
  if (p.x < 0.0 || p.z < 0.0) return "must not be negative";
  // The support box is the tile plus a voxel's trilinear reach each side.
  const glm::dvec2 v = voxel_xz(c);
  const auto shorter = [](const char* axis, double period, double extent) {
    return std::string("along ") + axis + " (" + number_text(period) + " m) is shorter than the cloud (" + number_text(extent) +
           " m): its copies would overlap";
  };
  if (p.x > 0.0 && p.x < (c.world_max.x - c.world_min.x) - 2.5 * v.x) return shorter("x", p.x, c.world_max.x - c.world_min.x);
  if (p.z > 0.0 && p.z < (c.world_max.z - c.world_min.z) - 2.5 * v.y) return shorter("z", p.z, c.world_max.z - c.world_min.z);
  // A tile is a whole number of voxels: a period under one voxel (a cloud of a voxel or two, which
  // the test above lets through) stacks copies within each voxel.
  const auto under_a_voxel = [](const char* axis, double period, double voxel) {
    return std::string("along ") + axis + " (" + number_text(period) + " m) is shorter than a voxel (" + number_text(voxel) +
           " m): its copies would overlap";
  };
  if (p.x > 0.0 && p.x < v.x) return under_a_voxel("x", p.x, v.x);
  if (p.z > 0.0 && p.z < v.y) return under_a_voxel("z", p.z, v.y);
  return "";
}

void validate_period(const CloudVolume& c) {
  const std::string fault = period_fault(c);
  if (!fault.empty()) throw std::invalid_argument("cloud '" + c.name + "': period " + fault);
}

CloudTilePlan plan_cloud_tiles(const std::vector<CloudVolume>& clouds, const Camera& camera, double repeat_to_m) {
  CloudTilePlan plan;
  const bool tiles = repeat_to_m > 0.0 && std::any_of(clouds.begin(), clouds.end(), periodic);
  for (std::size_t j = 0; j < clouds.size(); ++j)
    plan.near.push_back({j, tiles && periodic(clouds[j]) ? eye_offset(clouds[j], camera.eye) : glm::dvec3(0.0)});
  if (!tiles) return plan;
  const glm::dvec3 eye = camera.eye;

  // The near region: what the near list covers, grown by the copies that reach into it (twice:
  // a copy taken in can widen it), each copy's box shrunk by two voxels (its trilinear reach
  // over the tile's edge is not an overlap).
  const auto box_of = [&](const CloudInstance& i, glm::dvec3& lo, glm::dvec3& hi) {
    lo = clouds[i.cloud].world_min + i.offset_m;
    hi = clouds[i.cloud].world_max + i.offset_m;
  };
  const auto in_near = [&](std::size_t j, const glm::dvec3& o) {
    return std::any_of(plan.near.begin(), plan.near.end(),
                       [&](const CloudInstance& i) { return i.cloud == j && glm::all(glm::equal(i.offset_m, o)); });
  };
  // Copies of cloud j, a from its eye copy by (a, b) periods, within the per-axis limit.
  const auto repeats = [&](double period) {
    if (!(period > 0.0)) return 0;
    return static_cast<int>(std::min<double>(kMaxRepeatsPerAxis, std::ceil(repeat_to_m / period) + 1.0));
  };
  const auto for_each_copy = [&](auto&& f) {
    for (std::size_t j = 0; j < clouds.size(); ++j) {
      const CloudVolume& c = clouds[j];
      if (!periodic(c)) continue;
      const glm::dvec3 base = eye_offset(c, eye);
      const int na = repeats(c.period_m.x), nb = repeats(c.period_m.z);
      for (int a = -na; a <= na; ++a)
        for (int b = -nb; b <= nb; ++b) f(j, base + glm::dvec3(a * c.period_m.x, 0.0, b * c.period_m.z));
    }
  };
  for (int pass = 0; pass < 2; ++pass) {
    Rect region;
    for (const CloudInstance& i : plan.near) {
      glm::dvec3 lo, hi;
      box_of(i, lo, hi);
      region.add(lo, hi);
    }
    for_each_copy([&](std::size_t j, const glm::dvec3& o) {
      const glm::dvec3 lo = clouds[j].world_min + o, hi = clouds[j].world_max + o;
      if (!in_near(j, o) && region.overlaps(lo, hi, 2.0 * voxel_xz(clouds[j]))) plan.near.push_back({j, o});
    });
  }

  // The far copies: within reach, in view, nearest first.
  const glm::dmat4 view_proj = projection_matrix(camera) * view_matrix(camera);
  std::vector<std::pair<double, CloudInstance>> far;
  for_each_copy([&](std::size_t j, const glm::dvec3& o) {
    const glm::dvec3 lo = clouds[j].world_min + o, hi = clouds[j].world_max + o;
    const double d = xz_distance(eye, lo, hi);
    if (d > repeat_to_m || in_near(j, o) || outside_frustum(view_proj, lo, hi)) return;
    far.push_back({d, CloudInstance{j, o}});
  });
  std::stable_sort(far.begin(), far.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  if (far.size() > kMaxFarCopies) {
    plan.left_out = far.size() - kMaxFarCopies;
    far.resize(kMaxFarCopies);
  }
  for (const auto& f : far) plan.far.push_back(f.second);
  return plan;
}

}  // namespace nimbus::render
