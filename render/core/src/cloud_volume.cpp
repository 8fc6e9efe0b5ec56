// Clouds for rendering and their trilinear density (cloud_volume.hpp).
#include "nimbus/render/core/cloud_volume.hpp"

#include <cmath>
#include <stdexcept>

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
  const openvdb::math::Transform& t = grid.transform();
  if (!t.isLinear()) throw std::invalid_argument("cloud '" + name + "': its transform is not affine");
  CloudVolume c;
  c.name = name;
  c.optics = optics;
  c.box = volume::dense_active_box(grid);
  if (c.box.values.empty()) throw std::invalid_argument("cloud '" + name + "': the grid has no active voxels");
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

double sample_density(const CloudVolume& c, const glm::dvec3& world_m) {
  const glm::dvec3 p = glm::dvec3(c.world_to_index * glm::dvec4(world_m, 1.0));
  // Box-local index coordinates; voxel centres at integers, zero outside [0, size).
  double f[3];
  int64_t i0[3];
  for (int a = 0; a < 3; ++a) {
    const double x = p[a] - c.box.origin[a];
    if (!(x > -1.0 && x < static_cast<double>(c.box.size[a]))) return 0.0;
    const double fl = std::floor(x);
    i0[a] = static_cast<int64_t>(fl);
    f[a] = x - fl;
  }
  const int64_t nx = c.box.size[0], ny = c.box.size[1], nz = c.box.size[2];
  auto at = [&](int64_t i, int64_t j, int64_t k) -> double {
    if (i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz) return 0.0;
    return c.box.values[static_cast<std::size_t>(i + nx * (j + ny * k))];
  };
  double v = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const int dx = corner & 1, dy = (corner >> 1) & 1, dz = (corner >> 2) & 1;
    const double w = (dx ? f[0] : 1.0 - f[0]) * (dy ? f[1] : 1.0 - f[1]) * (dz ? f[2] : 1.0 - f[2]);
    if (w != 0.0) v += w * at(i0[0] + dx, i0[1] + dy, i0[2] + dz);
  }
  return v;
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
