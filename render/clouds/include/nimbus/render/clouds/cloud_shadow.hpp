// Building the clouds' shadow in the scene (gl/cloud_shadow_map.hpp): the optical depth through
// every cloud along the sun's direction, marched on the GPU over the clouds' footprint.
// View-independent, so built once per light and set of clouds.
#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/cloud_volume.hpp"
#include "nimbus/render/gl/cloud_shadow_map.hpp"
#include "nimbus/render/gl/shader_program.hpp"
#include "nimbus/render/gl/volume_texture.hpp"

namespace nimbus::render {

// Marches each texel's light ray through the clouds (half-voxel steps). Points between the
// nearest and farthest depth see tau scaled linearly between them; before, none; beyond, all.
// Needs a current GL 4.5 context; `textures` are the clouds uploaded in the same order.
// The same with the compute program compiled once (a sequence builds one map per frame).
class CloudShadowBuilder {
 public:
  CloudShadowBuilder();  // compiles; needs a current GL 4.5 context
  // `next_textures`: each cloud's next keyframe (nullptr: none; empty: none for all), blended
  // by the cloud's `blend` as the slicer does.
  CloudShadowMap build(const std::vector<CloudVolume>& clouds, const std::vector<const VolumeTexture*>& textures,
                       const Light& light, int resolution = 512,
                       const std::vector<const VolumeTexture*>& next_textures = {}) const;

 private:
  ShaderProgram program_;
};

CloudShadowMap build_cloud_shadow_map(const std::vector<CloudVolume>& clouds,
                                      const std::vector<const VolumeTexture*>& textures, const Light& light,
                                      int resolution = 512);

}  // namespace nimbus::render
