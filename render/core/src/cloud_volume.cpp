// Clouds for rendering and their trilinear density (cloud_volume.hpp).
#include "nimbus/render/core/cloud_volume.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace nimbus::render {
glm::dvec3 index_to_world(const openvdb::math::Transform& t, const glm::dvec3& index) {
  const openvdb::Vec3d w = t.indexToWorld(openvdb::Vec3d(index.x, index.y, index.z));
  return {w.x(), w.y(), w.z()};
}

glm::dmat4 index_to_world_matrix(const openvdb::math::Transform& transform) {
  if (!transform.isLinear()) throw std::invalid_argument("volume transform is not affine (frustum grids are not supported)");
  // Columns are the images of the index axes, then the origin.
  const glm::dvec3 o = index_to_world(transform, glm::dvec3(0, 0, 0));
  return glm::dmat4(glm::dvec4(index_to_world(transform, glm::dvec3(1, 0, 0)) - o, 0.0),
                    glm::dvec4(index_to_world(transform, glm::dvec3(0, 1, 0)) - o, 0.0),
                    glm::dvec4(index_to_world(transform, glm::dvec3(0, 0, 1)) - o, 0.0), glm::dvec4(o, 1.0));
}

CloudVolume make_cloud_volume(const openvdb::FloatGrid& grid, const CloudOptics& optics, const std::string& name) {
  validate(optics);
  if (!grid.transform().isLinear()) throw std::invalid_argument("cloud '" + name + "': its transform is not affine");
  return make_cloud_volume(volume::dense_active_box(grid), grid.transform(), optics, name);
}

CloudVolume make_cloud_volume(volume::DenseBox box, const openvdb::math::Transform& t, const CloudOptics& optics,
                              const std::string& name) {
  validate(optics);
  if (!t.isLinear()) throw std::invalid_argument("cloud '" + name + "': its transform is not affine");
  CloudVolume c;
  c.name = name;
  c.optics = optics;
  c.box = std::move(box);
  if (c.box.values.empty()) throw std::invalid_argument("cloud '" + name + "': the grid has no active voxels");
  if (c.box.values.size() != static_cast<std::size_t>(c.box.size[0] * c.box.size[1] * c.box.size[2]))
    throw std::invalid_argument("cloud '" + name + "': the box's values do not match its size");
  c.transform = t.copy();
  c.index_to_world = index_to_world_matrix(t);
  c.world_to_index = glm::inverse(c.index_to_world);
  c.world_min = glm::dvec3(1e300);
  c.world_max = glm::dvec3(-1e300);
  for (int k = 0; k < 8; ++k) {
    glm::dvec3 idx;
    for (int a = 0; a < 3; ++a)
      idx[a] = c.box.origin[a] - 1.0 + (((k >> a) & 1) ? static_cast<double>(c.box.size[a]) + 1.0 : 0.0);
    const glm::dvec3 w = glm::dvec3(c.index_to_world * glm::dvec4(idx, 1.0));
    c.world_min = glm::min(c.world_min, w);
    c.world_max = glm::max(c.world_max, w);
  }
  return c;
}

void set_next_keyframe(CloudVolume& cloud, volume::DenseBox next, double blend) {
  if (next.origin != cloud.box.origin || next.size != cloud.box.size || next.values.size() != cloud.box.values.size())
    throw std::invalid_argument("cloud '" + cloud.name + "': its next keyframe must lie on the same box");
  if (!(blend >= 0.0 && blend <= 1.0))
    throw std::invalid_argument("cloud '" + cloud.name + "': keyframe blend must be in [0, 1], got " + std::to_string(blend));
  cloud.next_box = std::move(next);
  cloud.blend = blend;
}

void translate(CloudVolume& c, const glm::dvec3& offset_m) {
  if (!std::isfinite(offset_m.x) || !std::isfinite(offset_m.y) || !std::isfinite(offset_m.z))
    throw std::invalid_argument("cloud '" + c.name + "': translation must be finite");
  c.index_to_world[3] += glm::dvec4(offset_m, 0.0);
  c.world_to_index = glm::inverse(c.index_to_world);
  if (c.transform) {
    c.transform = c.transform->copy();
    c.transform->postTranslate(openvdb::Vec3d(offset_m.x, offset_m.y, offset_m.z));
  }
  c.world_min += offset_m;
  c.world_max += offset_m;
}

void apply_motion(CloudVolume& c, const CloudMotion& m) {
  if (!(m.blend >= 0.0 && m.blend <= 1.0))
    throw std::invalid_argument("cloud '" + c.name + "': keyframe blend must be in [0, 1], got " + std::to_string(m.blend));
  if (m.blend > 0.0 && c.next_box.values.empty())
    throw std::invalid_argument("cloud '" + c.name + "': a keyframe blend needs a next keyframe");
  translate(c, m.offset_m);
  c.blend = m.blend;
}

namespace {

// Trilinear over one box at box-local index coordinates (voxel centres at integers, 0 outside).
double trilinear(const volume::DenseBox& b, const double f[3], const int64_t i0[3]) {
  const int64_t nx = b.size[0], ny = b.size[1], nz = b.size[2];
  if (i0[0] >= 0 && i0[1] >= 0 && i0[2] >= 0 && i0[0] + 1 < nx && i0[1] + 1 < ny && i0[2] + 1 < nz) {
    // Every corner inside (the photon tracer's tentative collisions, nearly always): the same
    // sum in the same order as below, without a bounds check per corner (an exact 0 weight adds
    // 0 to it, as skipping it does).
    const float* v0 = b.values.data() + static_cast<std::size_t>(i0[0] + nx * (i0[1] + ny * i0[2]));
    const std::size_t sy = static_cast<std::size_t>(nx), sz = static_cast<std::size_t>(nx * ny);
    const double gx[2] = {1.0 - f[0], f[0]}, gy[2] = {1.0 - f[1], f[1]}, gz[2] = {1.0 - f[2], f[2]};
    double v = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
      const int dx = corner & 1, dy = (corner >> 1) & 1, dz = (corner >> 2) & 1;
      v += gx[dx] * gy[dy] * gz[dz] * v0[dx + sy * dy + sz * dz];
    }
    return v;
  }
  auto at = [&](int64_t i, int64_t j, int64_t k) -> double {
    if (i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz) return 0.0;
    return b.values[static_cast<std::size_t>(i + nx * (j + ny * k))];
  };
  double v = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const int dx = corner & 1, dy = (corner >> 1) & 1, dz = (corner >> 2) & 1;
    const double w = (dx ? f[0] : 1.0 - f[0]) * (dy ? f[1] : 1.0 - f[1]) * (dz ? f[2] : 1.0 - f[2]);
    if (w != 0.0) v += w * at(i0[0] + dx, i0[1] + dy, i0[2] + dz);
  }
  return v;
}

}  // namespace

double sample_density(const CloudVolume& c, const glm::dvec3& world_m) {
  const glm::dvec3 p = glm::dvec3(c.world_to_index * glm::dvec4(world_m, 1.0));
  return sample_density_local(c, p - glm::dvec3(c.box.origin[0], c.box.origin[1], c.box.origin[2]));
}

double sample_density_local(const CloudVolume& c, const glm::dvec3& p) {
  // Box-local index coordinates; voxel centres at integers, zero outside (-1, size).
  double f[3];
  int64_t i0[3];
  for (int a = 0; a < 3; ++a) {
    const double x = p[a];
    if (!(x > -1.0 && x < static_cast<double>(c.box.size[a]))) return 0.0;
    const double fl = std::floor(x);
    i0[a] = static_cast<int64_t>(fl);
    f[a] = x - fl;
  }
  const double a = trilinear(c.box, f, i0);
  if (c.blend <= 0.0 || c.next_box.values.empty()) return a;
  return (1.0 - c.blend) * a + c.blend * trilinear(c.next_box, f, i0);
}

void cloud_bounds(const std::vector<CloudVolume>& clouds, glm::dvec3& world_min, glm::dvec3& world_max) {
  world_min = glm::dvec3(1e300);
  world_max = glm::dvec3(-1e300);
  for (const CloudVolume& c : clouds) {
    world_min = glm::min(world_min, c.world_min);
    world_max = glm::max(world_max, c.world_max);
  }
}

}  // namespace nimbus::render
