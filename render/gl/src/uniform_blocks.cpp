// Uniform blocks filled from the scene (uniform_blocks.hpp).
#include "nimbus/render/gl/uniform_blocks.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "nimbus/render/gl/to_float.hpp"

namespace nimbus::render {

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
       {{"LightsBlock.point_position[0]", offsetof(LightsBlock, point_position)},
        {"LightsBlock.point_intensity[0]", offsetof(LightsBlock, point_intensity)},
        {"LightsBlock.point_spot[0]", offsetof(LightsBlock, point_spot)},
        {"LightsBlock.point_cone[0]", offsetof(LightsBlock, point_cone)},
        {"LightsBlock.to_sun", offsetof(LightsBlock, to_sun)},
        {"LightsBlock.point_count", offsetof(LightsBlock, point_count)},
        {"LightsBlock.sun_irradiance", offsetof(LightsBlock, sun_irradiance)},
        {"LightsBlock.has_sun", offsetof(LightsBlock, has_sun)}}},
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
      {"SliceLightBlock",
       contract::BLOCK_SLICE_LIGHT,
       sizeof(SliceLightBlock),
       {{"SliceLightBlock.world_to_light_uv", offsetof(SliceLightBlock, world_to_light_uv)},
        {"SliceLightBlock.world_to_lamp_clip", offsetof(SliceLightBlock, world_to_lamp_clip)},
        {"SliceLightBlock.slice_axis", offsetof(SliceLightBlock, slice_axis)},
        {"SliceLightBlock.spacing_m", offsetof(SliceLightBlock, spacing_m)},
        {"SliceLightBlock.to_sun", offsetof(SliceLightBlock, to_sun)},
        {"SliceLightBlock.light_slab_m", offsetof(SliceLightBlock, light_slab_m)},
        {"SliceLightBlock.sun_irradiance", offsetof(SliceLightBlock, sun_irradiance)},
        {"SliceLightBlock.lamp_min_distance", offsetof(SliceLightBlock, lamp_min_distance)},
        {"SliceLightBlock.lamp_position", offsetof(SliceLightBlock, lamp_position)},
        {"SliceLightBlock.lamp_intensity", offsetof(SliceLightBlock, lamp_intensity)},
        {"SliceLightBlock.lamp_spot", offsetof(SliceLightBlock, lamp_spot)},
        {"SliceLightBlock.luv_eye", offsetof(SliceLightBlock, luv_eye)},
        {"SliceLightBlock.lamp_cos", offsetof(SliceLightBlock, lamp_cos)}}},
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
  b.point_count = static_cast<int>(scene.lamps.size());
  for (std::size_t i = 0; i < scene.lamps.size(); ++i) {
    b.point_position[i] = glm::vec4(to_float(scene.lamps[i].position_m), 1.0f);
    const Light& l = scene.lamps[i];
    b.point_intensity[i] = glm::vec4(to_float(l.intensity_w_sr), 0.0f);
    if (is_spot(l)) {
      b.point_spot[i] = glm::vec4(to_float(glm::normalize(l.spot_axis)), 1.0f);
      b.point_cone[i] = glm::vec4(static_cast<float>(std::cos(l.spot_outer_rad)),
                                  static_cast<float>(std::cos(l.spot_inner_rad)), 0.0f, 0.0f);
    }
  }
  if (scene.sun) {
    b.has_sun = 1;
    b.to_sun = to_float(glm::normalize(scene.sun->direction_to_sun));
    b.sun_irradiance = to_float(scene.sun->irradiance_w_m2);
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
