// Uniform blocks filled from the scene (uniform_blocks.hpp).
#include "nimbus/render/gl/uniform_blocks.hpp"

#include <cmath>
#include <utility>
#include <stdexcept>
#include <string>

#include "nimbus/render/gl/to_float.hpp"

namespace nimbus::render {
namespace {

// A LightRecord's four members as the GL names them under `prefix` (e.g. "LightsBlock.sun").
void add_record_members(std::vector<BlockMember>& members, const std::string& prefix, std::size_t offset) {
  const std::pair<const char*, std::size_t> fields[] = {{".position", offsetof(LightRecord, position)},
                                                        {".power", offsetof(LightRecord, power)},
                                                        {".spot", offsetof(LightRecord, spot)},
                                                        {".spot_cos", offsetof(LightRecord, spot_cos)}};
  for (const auto& [field, field_offset] : fields) members.push_back({prefix + field, offset + field_offset});
}

std::vector<BlockMember> lights_block_members() {
  std::vector<BlockMember> m;
  for (int i = 0; i < contract::MAX_POINT_LIGHTS; ++i)
    add_record_members(m, "LightsBlock.lamp[" + std::to_string(i) + "]", offsetof(LightsBlock, lamp) + i * sizeof(LightRecord));
  add_record_members(m, "LightsBlock.sun", offsetof(LightsBlock, sun));
  m.push_back({"LightsBlock.lamp_count", offsetof(LightsBlock, lamp_count)});
  m.push_back({"LightsBlock.has_sun", offsetof(LightsBlock, has_sun)});
  return m;
}

BlockLayout slice_light_layout() {
  BlockLayout l{"SliceLightBlock",
                contract::BLOCK_SLICE_LIGHT,
                sizeof(SliceLightBlock),
                {{"SliceLightBlock.world_to_light_uv", offsetof(SliceLightBlock, world_to_light_uv)},
                 {"SliceLightBlock.world_to_lamp_clip", offsetof(SliceLightBlock, world_to_lamp_clip)},
                 {"SliceLightBlock.slice_axis", offsetof(SliceLightBlock, slice_axis)},
                 {"SliceLightBlock.spacing_m", offsetof(SliceLightBlock, spacing_m)}}};
  add_record_members(l.members, "SliceLightBlock.light", offsetof(SliceLightBlock, light));
  l.members.push_back({"SliceLightBlock.luv_eye", offsetof(SliceLightBlock, luv_eye)});
  l.members.push_back({"SliceLightBlock.light_slab_m", offsetof(SliceLightBlock, light_slab_m)});
  return l;
}

}  // namespace

std::vector<BlockLayout> uniform_block_layouts() {
  return {
      {"CameraBlock",
       contract::BLOCK_CAMERA,
       sizeof(CameraBlock),
       {{"CameraBlock.view_proj", offsetof(CameraBlock, view_proj)},
        {"CameraBlock.eye", offsetof(CameraBlock, eye)},
        {"CameraBlock.near_m", offsetof(CameraBlock, near_m)},
        {"CameraBlock.forward", offsetof(CameraBlock, forward)},
        {"CameraBlock.right_scaled", offsetof(CameraBlock, right_scaled)},
        {"CameraBlock.up_scaled", offsetof(CameraBlock, up_scaled)},
        {"CameraBlock.viewport", offsetof(CameraBlock, viewport)},
        {"CameraBlock.pixel_offset", offsetof(CameraBlock, pixel_offset)}}},
      {"LightsBlock",
       contract::BLOCK_LIGHTS,
       sizeof(LightsBlock),
       lights_block_members()},
      {"CloudBlock",
       contract::BLOCK_CLOUD,
       sizeof(CloudBlock),
       {{"CloudBlock.world_to_texture", offsetof(CloudBlock, world_to_texture)},
        {"CloudBlock.albedo", offsetof(CloudBlock, albedo)},
        {"CloudBlock.sigma_t", offsetof(CloudBlock, sigma_t)},
        {"CloudBlock.ambient", offsetof(CloudBlock, ambient)},
        {"CloudBlock.tau_per_density", offsetof(CloudBlock, tau_per_density)},
        {"CloudBlock.phase", offsetof(CloudBlock, phase)},
        {"CloudBlock.blend", offsetof(CloudBlock, blend)},
        {"CloudBlock.tc_eye", offsetof(CloudBlock, tc_eye)},
        {"CloudBlock.copy_offset_m", offsetof(CloudBlock, copy_offset_m)}}},
      slice_light_layout(),
      {"CloudShadowMarchBlock",
       contract::BLOCK_CLOUD_SHADOW_MARCH,
       sizeof(CloudShadowMarchBlock),
       {{"CloudShadowMarchBlock.origin", offsetof(CloudShadowMarchBlock, origin)},
        {"CloudShadowMarchBlock.res", offsetof(CloudShadowMarchBlock, res)},
        {"CloudShadowMarchBlock.axis_x", offsetof(CloudShadowMarchBlock, axis_x)},
        {"CloudShadowMarchBlock.steps", offsetof(CloudShadowMarchBlock, steps)},
        {"CloudShadowMarchBlock.axis_y", offsetof(CloudShadowMarchBlock, axis_y)},
        {"CloudShadowMarchBlock.depth0", offsetof(CloudShadowMarchBlock, depth0)},
        {"CloudShadowMarchBlock.to_sun", offsetof(CloudShadowMarchBlock, to_sun)},
        {"CloudShadowMarchBlock.step_m", offsetof(CloudShadowMarchBlock, step_m)},
        {"CloudShadowMarchBlock.box_min", offsetof(CloudShadowMarchBlock, box_min)},
        {"CloudShadowMarchBlock.box_max", offsetof(CloudShadowMarchBlock, box_max)}}},
      {"ShadowMapBlock",
       contract::BLOCK_SHADOW_MAP,
       sizeof(ShadowMapBlock),
       {{"ShadowMapBlock.origin", offsetof(ShadowMapBlock, origin)},
        {"ShadowMapBlock.mode", offsetof(ShadowMapBlock, mode)},
        {"ShadowMapBlock.to_sun", offsetof(ShadowMapBlock, to_sun)},
        {"ShadowMapBlock.layer", offsetof(ShadowMapBlock, layer)},
        {"ShadowMapBlock.axis_x", offsetof(ShadowMapBlock, axis_x)},
        {"ShadowMapBlock.res", offsetof(ShadowMapBlock, res)},
        {"ShadowMapBlock.axis_y", offsetof(ShadowMapBlock, axis_y)},
        {"ShadowMapBlock.rel_threshold", offsetof(ShadowMapBlock, rel_threshold)},
        {"ShadowMapBlock.max_distance", offsetof(ShadowMapBlock, max_distance)},
        {"ShadowMapBlock.max_quads", offsetof(ShadowMapBlock, max_quads)}}},
      {"SceneShadowsBlock",
       contract::BLOCK_SCENE_SHADOWS,
       sizeof(SceneShadowsBlock),
       {{"SceneShadowsBlock.sun_origin", offsetof(SceneShadowsBlock, sun_origin)},
        {"SceneShadowsBlock.point_bias", offsetof(SceneShadowsBlock, point_bias)},
        {"SceneShadowsBlock.sun_axis_x", offsetof(SceneShadowsBlock, sun_axis_x)},
        {"SceneShadowsBlock.sun_bias", offsetof(SceneShadowsBlock, sun_bias)},
        {"SceneShadowsBlock.sun_axis_y", offsetof(SceneShadowsBlock, sun_axis_y)},
        {"SceneShadowsBlock.point_texel_angle", offsetof(SceneShadowsBlock, point_texel_angle)},
        {"SceneShadowsBlock.sun_texel_m", offsetof(SceneShadowsBlock, sun_texel_m)}}},
      {"SkyBlock",
       contract::BLOCK_SKY,
       sizeof(SkyBlock),
       {{"SkyBlock.zenith", offsetof(SkyBlock, zenith)},
        {"SkyBlock.has_sky", offsetof(SkyBlock, has_sky)},
        {"SkyBlock.horizon", offsetof(SkyBlock, horizon)},
        {"SkyBlock.physical", offsetof(SkyBlock, physical)},
        {"SkyBlock.sun", offsetof(SkyBlock, sun)},
        {"SkyBlock.cos_horizon", offsetof(SkyBlock, cos_horizon)},
        {"SkyBlock.distance_m", offsetof(SkyBlock, distance_m)},
        {"SkyBlock.aerial_on", offsetof(SkyBlock, aerial_on)},
        {"SkyBlock.aerial_max_distance_m", offsetof(SkyBlock, aerial_max_distance_m)}}},
      {"LightVolumeBlock",
       contract::BLOCK_LIGHT_VOLUME,
       sizeof(LightVolumeBlock),
       {{"LightVolumeBlock.world_min", offsetof(LightVolumeBlock, world_min)},
        {"LightVolumeBlock.cell_m", offsetof(LightVolumeBlock, cell_m)},
        {"LightVolumeBlock.cells", offsetof(LightVolumeBlock, cells)},
        {"LightVolumeBlock.light_dir", offsetof(LightVolumeBlock, light_dir)}}},
      {"ShaftPassBlock",
       contract::BLOCK_SHAFT_PASS,
       sizeof(ShaftPassBlock),
       {{"ShaftPassBlock.march_cutoff_m", offsetof(ShaftPassBlock, march_cutoff_m)},
        {"ShaftPassBlock.shadow_ceiling_m", offsetof(ShaftPassBlock, shadow_ceiling_m)},
        {"ShaftPassBlock.jitter_mode", offsetof(ShaftPassBlock, jitter_mode)},
        {"ShaftPassBlock.jitter_shift", offsetof(ShaftPassBlock, jitter_shift)},
        {"ShaftPassBlock.f_table_size", offsetof(ShaftPassBlock, f_table_size)}}},
      {"SurfaceDrawBlock",
       contract::BLOCK_SURFACE_DRAW,
       sizeof(SurfaceDrawBlock),
       {{"SurfaceDrawBlock.emissive_radiance", offsetof(SurfaceDrawBlock, emissive_radiance)},
        {"SurfaceDrawBlock.emissive", offsetof(SurfaceDrawBlock, emissive)},
        {"SurfaceDrawBlock.sky_irradiance_up", offsetof(SurfaceDrawBlock, sky_irradiance_up)},
        {"SurfaceDrawBlock.normal_offset_texels", offsetof(SurfaceDrawBlock, normal_offset_texels)},
        {"SurfaceDrawBlock.is_ground", offsetof(SurfaceDrawBlock, is_ground)},
        {"SurfaceDrawBlock.ground_height_m", offsetof(SurfaceDrawBlock, ground_height_m)},
        {"SurfaceDrawBlock.ground_textured", offsetof(SurfaceDrawBlock, ground_textured)}}},
      {"GroundAlbedoBlock",
       contract::BLOCK_GROUND_ALBEDO,
       sizeof(GroundAlbedoBlock),
       {{"GroundAlbedoBlock.period_m", offsetof(GroundAlbedoBlock, period_m)},
        {"GroundAlbedoBlock.texels", offsetof(GroundAlbedoBlock, texels)},
        {"GroundAlbedoBlock.mean_luminance", offsetof(GroundAlbedoBlock, mean_luminance)}}},
  };
}

CameraBlock camera_block(const Camera& camera) {
  CameraBlock b;
  const CameraFrame frame = camera_frame(camera);
  const double tan_half = std::tan(0.5 * camera.fov_deg * M_PI / 180.0);
  b.view_proj = to_float(projection_matrix(camera) * view_matrix(camera));
  b.eye = to_float(camera.eye);
  b.near_m = static_cast<float>(camera.near_m);
  b.forward = to_float(frame.forward);
  b.right_scaled = to_float(frame.right * tan_half);
  b.up_scaled = to_float(frame.up * (tan_half * camera.height / camera.width));
  b.viewport = glm::vec2(static_cast<float>(camera.width), static_cast<float>(camera.height));
  b.pixel_offset = glm::vec2(static_cast<float>(camera.pixel_offset.x), static_cast<float>(-camera.pixel_offset.y));
  return b;
}

LightsBlock no_lights_block() { return LightsBlock{}; }

LightsBlock lights_block(const Scene& scene) {
  if (scene.lamps.size() > static_cast<std::size_t>(contract::MAX_POINT_LIGHTS))
    throw std::invalid_argument("scene '" + scene.name + "': the GPU takes at most " +
                                std::to_string(contract::MAX_POINT_LIGHTS) + " point lights, got " +
                                std::to_string(scene.lamps.size()));
  LightsBlock b;
  b.lamp_count = static_cast<int>(scene.lamps.size());
  for (std::size_t i = 0; i < scene.lamps.size(); ++i) b.lamp[i] = light_record(scene.lamps[i]);
  if (scene.sun) {
    b.has_sun = 1;
    b.sun = light_record(*scene.sun);
  }
  return b;
}

std::size_t aligned_stride(std::size_t size) {
  GLint align = 0;
  glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &align);
  const std::size_t a = align > 0 ? static_cast<std::size_t>(align) : 256;
  return (size + a - 1) / a * a;
}

}  // namespace nimbus::render
