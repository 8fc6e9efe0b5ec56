// The clouds' shadow map for the scene's surfaces and shafts (cloud_shadow.hpp).
#include "nimbus/render/clouds/cloud_shadow.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nimbus/render/core/shader_contract.hpp"
#include "nimbus/render/gl/shader_program.hpp"
#include "nimbus/render/gl/to_float.hpp"
#include "nimbus/render/gl/uniform_blocks.hpp"

namespace nimbus::render {
namespace {

// An orthonormal pair perpendicular to unit d.
void basis(const glm::dvec3& d, glm::dvec3& u, glm::dvec3& v) {
  const glm::dvec3 helper = std::abs(d.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  u = glm::normalize(glm::cross(helper, d));
  v = glm::cross(d, u);
}

double voxel_size_m(const CloudVolume& c) {
  double s = 1e300;
  for (int a = 0; a < 3; ++a) s = std::min(s, glm::length(glm::dvec3(c.index_to_world[a])));
  return s;
}

}  // namespace

CloudShadowBuilder::CloudShadowBuilder() : program_({"cloud_shadow_build.comp.glsl"}) {}

CloudShadowMap build_cloud_shadow_map(const std::vector<CloudVolume>& clouds,
                                      const std::vector<const VolumeTexture*>& textures, const Light& light,
                                      int resolution) {
  return CloudShadowBuilder().build(clouds, textures, light, resolution);
}

CloudShadowMap CloudShadowBuilder::build(const std::vector<CloudVolume>& clouds,
                                         const std::vector<const VolumeTexture*>& textures, const Light& light,
                                         int resolution, const std::vector<const VolumeTexture*>& next_textures) const {
  validate(light);
  if (light.kind != LightKind::Sun)
    throw std::invalid_argument("cloud shadow map light: the clouds cast their shadow on the scene from the sun only");
  if (clouds.empty()) throw std::invalid_argument("cloud shadow map: no clouds");
  if (textures.size() != clouds.size())
    throw std::invalid_argument("cloud shadow map: " + std::to_string(textures.size()) + " textures for " +
                                std::to_string(clouds.size()) + " clouds");
  if (!next_textures.empty() && next_textures.size() != clouds.size())
    throw std::invalid_argument("cloud shadow map: " + std::to_string(next_textures.size()) + " next keyframes for " +
                                std::to_string(clouds.size()) + " clouds");
  if (resolution < 16 || resolution > 8192)
    throw std::invalid_argument("cloud shadow map resolution must be in [16, 8192], got " + std::to_string(resolution));
  const glm::dvec3 dir = -glm::normalize(light.direction_to_sun);  // propagation
  glm::dvec3 u, v;
  basis(dir, u, v);

  // Footprint of every cloud's support box (its 8 corners) in (u, v, dir).
  glm::dvec3 lo(1e300), hi(-1e300);
  CloudShadowMap map;
  for (const CloudVolume& c : clouds) {
    for (int k = 0; k < 8; ++k) {
      const glm::dvec3 p(k & 1 ? c.world_max.x : c.world_min.x, k & 2 ? c.world_max.y : c.world_min.y,
                         k & 4 ? c.world_max.z : c.world_min.z);
      const glm::dvec3 q(glm::dot(p, u), glm::dot(p, v), glm::dot(p, dir));
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
    }
    map.top_y_m = std::max(map.top_y_m, c.world_max.y);
  }
  const glm::dvec3 pad = 0.5 * (hi - lo) / static_cast<double>(resolution) + glm::dvec3(1e-6);
  lo -= pad;
  hi += pad;
  const glm::dvec3 origin = lo.x * u + lo.y * v + lo.z * dir;
  const glm::dvec3 axis_x = (hi.x - lo.x) * u, axis_y = (hi.y - lo.y) * v;
  // World -> map: x, y across the footprint, z = metres along dir from the plane through origin.
  glm::dmat4 m(0.0);
  const glm::dvec3 rx = u / (hi.x - lo.x), ry = v / (hi.y - lo.y);
  for (int c = 0; c < 3; ++c) {
    m[c][0] = rx[c];
    m[c][1] = ry[c];
    m[c][2] = dir[c];
  }
  m[3][0] = -glm::dot(rx, origin);
  m[3][1] = -glm::dot(ry, origin);
  m[3][2] = -glm::dot(dir, origin);
  m[3][3] = 1.0;
  map.world_to_map = m;
  map.resolution = resolution;

  map.optical_depth = make_texture_2d(GL_R32F, resolution, resolution,
                                      TextureParams{GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_BORDER, 1});
  map.depth_range = make_texture_2d(GL_RG32F, resolution, resolution,
                                    TextureParams{GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE, 1});
  const float zero[4] = {0, 0, 0, 0};
  const float empty_range[4] = {3.0e38f, -3.0e38f, 0, 0};
  glClearTexImage(map.optical_depth.id(), 0, GL_RED, GL_FLOAT, zero);
  glClearTexImage(map.depth_range.id(), 0, GL_RG, GL_FLOAT, empty_range);

  const ShaderProgram& p = program_;
  p.use();
  glBindImageTexture(contract::IMAGE_CLOUD_TAU, map.optical_depth.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
  glBindImageTexture(contract::IMAGE_CLOUD_RANGE, map.depth_range.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RG32F);
  // Each cloud's block: its density texture's map and extinction (the rest is the slicer's).
  std::vector<CloudBlock> blocks(clouds.size());
  for (std::size_t i = 0; i < clouds.size(); ++i) {
    blocks[i].world_to_texture = glm::mat4(textures[i]->world_to_texture);
    blocks[i].sigma_t = static_cast<float>(clouds[i].optics.extinction_per_m);
    const bool next = !next_textures.empty() && next_textures[i];
    blocks[i].blend = next ? static_cast<float>(clouds[i].blend) : 0.0f;
  }
  UniformArray<CloudBlock> cloud_ubo;
  cloud_ubo.update(blocks);
  // Each cloud's march: the map's plane, and the cloud's depth range along dir in half-voxel steps.
  std::vector<CloudShadowMarchBlock> marches(clouds.size());
  for (std::size_t i = 0; i < clouds.size(); ++i) {
    const CloudVolume& c = clouds[i];
    double d0 = 1e300, d1 = -1e300;
    for (int k = 0; k < 8; ++k) {
      const glm::dvec3 q(k & 1 ? c.world_max.x : c.world_min.x, k & 2 ? c.world_max.y : c.world_min.y,
                         k & 4 ? c.world_max.z : c.world_min.z);
      const double d = glm::dot(q - origin, dir);
      d0 = std::min(d0, d);
      d1 = std::max(d1, d);
    }
    const double step = 0.5 * voxel_size_m(c);
    const int steps = std::max(1, static_cast<int>(std::ceil((d1 - d0) / step)));
    CloudShadowMarchBlock& march = marches[i];
    march.origin = to_float(origin);
    march.axis_x = to_float(axis_x);
    march.axis_y = to_float(axis_y);
    march.to_sun = to_float(-dir);
    march.res = resolution;
    march.depth0 = static_cast<float>(d0);
    march.step_m = static_cast<float>((d1 - d0) / steps);
    march.steps = steps;
    march.box_min = to_float(c.world_min);
    march.box_max = to_float(c.world_max);
  }
  UniformArray<CloudShadowMarchBlock> march_ubo;
  march_ubo.update(marches);
  const GLuint groups = static_cast<GLuint>((resolution + 7) / 8);
  for (std::size_t i = 0; i < clouds.size(); ++i) {
    cloud_ubo.bind(contract::BLOCK_CLOUD, i);
    march_ubo.bind(contract::BLOCK_CLOUD_SHADOW_MARCH, i);
    glBindTextureUnit(contract::UNIT_CLOUD_DENSITY, textures[i]->texture.id());
    const bool next = !next_textures.empty() && next_textures[i];
    glBindTextureUnit(contract::UNIT_CLOUD_DENSITY_NEXT, (next ? next_textures[i] : textures[i])->texture.id());
    glDispatchCompute(groups, groups, 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }
  check_gl("building the cloud shadow map");
  return map;
}

}  // namespace nimbus::render
