// The shaders' uniform blocks as checked C++ structs (std140, shaders/lib/contract.glsl's
// BLOCK_* bindings): the camera, the scene's lights, one cloud and the slicer pass's light (both light
// blocks hold LightRecords, lib/light_record.glsl). Each struct's offsets are
// static_asserted against the std140 rules here, and tests/gl/test_contract.cpp checks them
// against the offsets the GL reports for every program that uses the block. Builders fill them
// from the scene's double-precision values exactly as the shaders expect them.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstring>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/light_record.hpp"
#include "nimbus/render/scene/scene.hpp"
#include "nimbus/render/core/shader_contract.hpp"
#include "nimbus/render/gl/resources.hpp"

namespace nimbus::render {

// lib/camera_ray.glsl: CameraBlock.
struct CameraBlock {
  glm::mat4 view_proj{1.0f};  // world -> clip
  glm::vec3 eye{0.0f};        // metres
  float near_m = 0.0f;        // the near plane, metres
  glm::vec3 forward{0.0f};    // unit
  float pad0 = 0.0f;
  glm::vec3 right_scaled{0.0f};  // right * tan(fov/2)
  float pad1 = 0.0f;
  glm::vec3 up_scaled{0.0f};  // up * tan(fov/2) * height / width
  float pad2 = 0.0f;
  glm::vec2 viewport{0.0f};   // width, height in pixels
  glm::vec2 pixel_offset{0.0f};  // Camera::pixel_offset in GL window pixels (y up)
};
static_assert(offsetof(CameraBlock, view_proj) == 0 && offsetof(CameraBlock, eye) == 64 &&
              offsetof(CameraBlock, near_m) == 76 && offsetof(CameraBlock, forward) == 80 &&
              offsetof(CameraBlock, right_scaled) == 96 && offsetof(CameraBlock, up_scaled) == 112 &&
              offsetof(CameraBlock, viewport) == 128 &&
              offsetof(CameraBlock, pixel_offset) == 136 && sizeof(CameraBlock) == 144,
              "CameraBlock must follow std140 as lib/camera_ray.glsl declares it");

// lib/light_list.glsl: LightsBlock, the scene's lights, each a LightRecord (light_record.hpp).
struct LightsBlock {
  LightRecord lamp[contract::MAX_POINT_LIGHTS] = {};  // the lamps, lamp_count of them in use
  LightRecord sun = no_light_record();                 // the sun (no_light_record() when has_sun is 0)
  int lamp_count = 0;
  int has_sun = 0;
  int pad0 = 0, pad1 = 0;  // the block's size rounds up to a vec4 (as the GL reports it)
};
static_assert(offsetof(LightsBlock, lamp) == 0 && offsetof(LightsBlock, sun) == 64 * contract::MAX_POINT_LIGHTS &&
                  offsetof(LightsBlock, lamp_count) == 64 * contract::MAX_POINT_LIGHTS + 64 &&
                  offsetof(LightsBlock, has_sun) == 64 * contract::MAX_POINT_LIGHTS + 68 &&
                  sizeof(LightsBlock) == 64 * contract::MAX_POINT_LIGHTS + 80,
              "LightsBlock must follow std140 as lib/light_list.glsl declares it");

// lib/cloud_block.glsl: CloudBlock, one per cloud.
struct CloudBlock {
  glm::mat4 world_to_texture{1.0f};  // world -> density-texture coordinates
  glm::vec3 albedo{0.0f};            // sigma_s / sigma_t per channel
  float sigma_t = 0.0f;              // extinction per unit density, per metre
  glm::vec3 ambient{0.0f};           // sky radiance on the cloud (0 when off)
  float tau_per_density = 0.0f;      // a slab's optical depth along the light per unit density
  glm::vec3 phase{0.0f};             // g_forward, g_back, forward weight
  float blend = 0.0f;                // weight of the next keyframe's density, [0, 1]
  glm::vec3 tc_eye{0.0f};            // the eye's density-texture coordinates
  float pad1 = 0.0f;
  glm::vec3 copy_offset_m{0.0f};     // a periodic tile's copy: its offset from the cloud (cloud_tiles.hpp), metres
  float pad2 = 0.0f;
};
static_assert(offsetof(CloudBlock, world_to_texture) == 0 && offsetof(CloudBlock, albedo) == 64 &&
              offsetof(CloudBlock, sigma_t) == 76 && offsetof(CloudBlock, ambient) == 80 &&
              offsetof(CloudBlock, tau_per_density) == 92 && offsetof(CloudBlock, phase) == 96 && offsetof(CloudBlock, blend) == 108 &&
              offsetof(CloudBlock, tc_eye) == 112 && offsetof(CloudBlock, copy_offset_m) == 128 && sizeof(CloudBlock) == 144,
              "CloudBlock must follow std140 as lib/cloud_block.glsl declares it");

// lib/cloud_light_block.glsl: SliceLightBlock, the light of the slicer's current pass (the sun,
// a lamp or a spot: one LightRecord, as in LightsBlock) with the pass's slicing geometry.
struct SliceLightBlock {
  glm::mat4 world_to_light_uv{1.0f};       // the sun: world -> its light buffer's (u, w)
  glm::mat4 world_to_lamp_clip{1.0f};      // a lamp: world -> its light buffer's clip coordinates
  glm::vec3 slice_axis{0.0f, 0.0f, 1.0f};  // s, unit
  float spacing_m = 0.0f;                  // d
  LightRecord light = no_light_record();   // the pass's light
  glm::vec2 luv_eye{0.0f};                 // the sun: the eye's light-buffer coordinates
  float light_slab_m = 0.0f;               // the sun: d / |dot(l, s)|
  float pad0 = 0.0f;                       // the block's size rounds up to a vec4 (as the GL reports it)
};
static_assert(offsetof(SliceLightBlock, world_to_light_uv) == 0 && offsetof(SliceLightBlock, world_to_lamp_clip) == 64 &&
                  offsetof(SliceLightBlock, slice_axis) == 128 && offsetof(SliceLightBlock, spacing_m) == 140 &&
                  offsetof(SliceLightBlock, light) == 144 && offsetof(SliceLightBlock, luv_eye) == 208 &&
                  offsetof(SliceLightBlock, light_slab_m) == 216 && sizeof(SliceLightBlock) == 224,
              "SliceLightBlock must follow std140 as lib/cloud_light_block.glsl declares it");

// cloud_shadow_build.comp.glsl: CloudShadowMarchBlock, the march of one cloud through the clouds'
// shadow map (cloud_shadow.hpp), one per cloud.
struct CloudShadowMarchBlock {
  glm::vec3 origin{0.0f};   // world point of the map's corner (texel 0, 0) on its plane, metres
  int res = 0;              // texels per side
  glm::vec3 axis_x{0.0f};   // map width vector, metres
  int steps = 0;            // steps of the march
  glm::vec3 axis_y{0.0f};   // map height vector, metres
  float depth0 = 0.0f;      // the march starts at this depth, metres along the light from the plane
  glm::vec3 to_sun{0.0f};   // unit, towards the sun
  float step_m = 0.0f;      // the step, metres
  glm::vec3 box_min{0.0f};  // the cloud's support, world metres
  float pad0 = 0.0f;
  glm::vec3 box_max{0.0f};
  float pad1 = 0.0f;
};
static_assert(offsetof(CloudShadowMarchBlock, origin) == 0 && offsetof(CloudShadowMarchBlock, res) == 12 &&
                  offsetof(CloudShadowMarchBlock, axis_x) == 16 && offsetof(CloudShadowMarchBlock, steps) == 28 &&
                  offsetof(CloudShadowMarchBlock, axis_y) == 32 && offsetof(CloudShadowMarchBlock, depth0) == 44 &&
                  offsetof(CloudShadowMarchBlock, to_sun) == 48 && offsetof(CloudShadowMarchBlock, step_m) == 60 &&
                  offsetof(CloudShadowMarchBlock, box_min) == 64 && offsetof(CloudShadowMarchBlock, box_max) == 80 &&
                  sizeof(CloudShadowMarchBlock) == 96,
              "CloudShadowMarchBlock must follow std140 as cloud_shadow_build.comp.glsl declares it");

// lib/shadow_map_block.glsl: ShadowMapBlock, the light a shadow map is made for and the limits of
// the skirts built from it (the light-shaft renderer's shadow maps and shadow volumes).
struct ShadowMapBlock {
  glm::vec3 origin{0.0f};     // the lamp's position, or the sun map's corner, metres
  int mode = 0;               // contract::SHADOW_POINT_LIGHT or SHADOW_SUN
  glm::vec3 to_sun{0.0f};     // unit, towards the sun
  int layer = 0;              // the lamp's cube-map layer, or the sun's (after the lamps)
  glm::vec3 axis_x{0.0f};     // the sun map's width vector, metres
  int res = 0;                // texels per side of each face
  glm::vec3 axis_y{0.0f};     // the sun map's height vector, metres
  float rel_threshold = 0.0f; // relative distance jump that makes a silhouette
  float max_distance = 0.0f;  // skirts end here, metres
  unsigned max_quads = 0;     // the skirts' buffer holds this many quads
  float pad0 = 0.0f, pad1 = 0.0f;  // the block's size rounds up to a vec4
};
static_assert(offsetof(ShadowMapBlock, origin) == 0 && offsetof(ShadowMapBlock, mode) == 12 &&
                  offsetof(ShadowMapBlock, to_sun) == 16 && offsetof(ShadowMapBlock, layer) == 28 &&
                  offsetof(ShadowMapBlock, axis_x) == 32 && offsetof(ShadowMapBlock, res) == 44 &&
                  offsetof(ShadowMapBlock, axis_y) == 48 && offsetof(ShadowMapBlock, rel_threshold) == 60 &&
                  offsetof(ShadowMapBlock, max_distance) == 64 && offsetof(ShadowMapBlock, max_quads) == 68 &&
                  sizeof(ShadowMapBlock) == 80,
              "ShadowMapBlock must follow std140 as lib/shadow_map_block.glsl declares it");

// lib/lights.glsl: SceneShadowsBlock, the light-shaft renderer's shadow maps as their lookups read
// them: the sun map's plane and texel, and both maps' biases.
struct SceneShadowsBlock {
  glm::vec3 sun_origin{0.0f};      // the sun map's corner, metres
  float point_bias = 0.0f;         // relative distance bias of the lamps' cube maps
  glm::vec3 sun_axis_x{0.0f};      // the sun map's width vector, metres
  float sun_bias = 0.0f;           // metres
  glm::vec3 sun_axis_y{0.0f};      // the sun map's height vector, metres
  float point_texel_angle = 0.0f;  // a cube-map texel's angle at a face centre, radians
  float sun_texel_m = 0.0f;        // a sun-map texel, metres
  float pad0 = 0.0f, pad1 = 0.0f, pad2 = 0.0f;  // the block's size rounds up to a vec4
};
static_assert(offsetof(SceneShadowsBlock, sun_origin) == 0 && offsetof(SceneShadowsBlock, point_bias) == 12 &&
                  offsetof(SceneShadowsBlock, sun_axis_x) == 16 && offsetof(SceneShadowsBlock, sun_bias) == 28 &&
                  offsetof(SceneShadowsBlock, sun_axis_y) == 32 && offsetof(SceneShadowsBlock, point_texel_angle) == 44 &&
                  offsetof(SceneShadowsBlock, sun_texel_m) == 48 && sizeof(SceneShadowsBlock) == 64,
              "SceneShadowsBlock must follow std140 as lib/lights.glsl declares it");

// lib/sky_block.glsl: SkyBlock, the scene's sky: its gradient, and the physical sky's tables when
// they are bound (sky_block, atmosphere_textures.hpp).
struct SkyBlock {
  glm::vec3 zenith{0.0f};             // the gradient's zenith radiance, W sr^-1 m^-2
  int has_sky = 0;                    // 1: the scene has a sky
  glm::vec3 horizon{0.0f};            // the gradient's horizon radiance
  int physical = 0;                   // 1: the sky-view table; 0: the gradient
  glm::vec3 sun{0.0f};                // the physical sky's direction to the sun, unit
  float cos_horizon = 0.0f;           // cos of the horizon's zenith angle at the viewer
  float distance_m = 0.0f;            // the sky's distance, metres
  int aerial_on = 0;                  // 1: the aerial perspective's tables are bound
  float aerial_max_distance_m = 0.0f; // the tables' reach, metres
  float pad0 = 0.0f;                  // the block's size rounds up to a vec4
};
static_assert(offsetof(SkyBlock, zenith) == 0 && offsetof(SkyBlock, has_sky) == 12 && offsetof(SkyBlock, horizon) == 16 &&
                  offsetof(SkyBlock, physical) == 28 && offsetof(SkyBlock, sun) == 32 &&
                  offsetof(SkyBlock, cos_horizon) == 44 && offsetof(SkyBlock, distance_m) == 48 &&
                  offsetof(SkyBlock, aerial_on) == 52 && offsetof(SkyBlock, aerial_max_distance_m) == 56 &&
                  sizeof(SkyBlock) == 64,
              "SkyBlock must follow std140 as lib/sky_block.glsl declares it");

// lib/cloud_light_volume.glsl: LightVolumeBlock, the light volume's grid (cloud_renderer.hpp).
struct LightVolumeBlock {
  glm::vec3 world_min{0.0f};  // the grid's corner, metres
  float pad0 = 0.0f;
  glm::vec3 cell_m{0.0f};     // a cell's sides, metres per axis
  float pad1 = 0.0f;
  glm::vec3 cells{0.0f};      // cells per axis
  float pad2 = 0.0f;
  glm::vec3 light_dir{0.0f};  // the sun's direction of propagation, unit
  float pad3 = 0.0f;
};
static_assert(offsetof(LightVolumeBlock, world_min) == 0 && offsetof(LightVolumeBlock, cell_m) == 16 &&
                  offsetof(LightVolumeBlock, cells) == 32 && offsetof(LightVolumeBlock, light_dir) == 48 &&
                  sizeof(LightVolumeBlock) == 64,
              "LightVolumeBlock must follow std140 as lib/cloud_light_volume.glsl declares it");

// shafts.frag.glsl: ShaftPassBlock, the light-shaft pass's own values.
struct ShaftPassBlock {
  float march_cutoff_m = 0.0f;    // ray-march end for rays that hit nothing, metres
  float shadow_ceiling_m = 0.0f;  // nothing shadows the sun above this height, metres (1e30: none known)
  int jitter_mode = 0;            // jitter_code(...)
  float jitter_shift = 0.0f;      // this frame's shift of the jitter values, modulo 1
  int f_table_size = 0;           // the analytic method's F table, texels per side
  float pad0 = 0.0f, pad1 = 0.0f, pad2 = 0.0f;  // the block's size rounds up to a vec4
};
static_assert(offsetof(ShaftPassBlock, march_cutoff_m) == 0 && offsetof(ShaftPassBlock, shadow_ceiling_m) == 4 &&
                  offsetof(ShaftPassBlock, jitter_mode) == 8 && offsetof(ShaftPassBlock, jitter_shift) == 12 &&
                  offsetof(ShaftPassBlock, f_table_size) == 16 && sizeof(ShaftPassBlock) == 32,
              "ShaftPassBlock must follow std140 as shafts.frag.glsl declares it");

// surface.frag.glsl: SurfaceDrawBlock, what the surface pass draws now (the ground, the occluders
// or a bulb), updated between its draws.
struct SurfaceDrawBlock {
  glm::vec3 emissive_radiance{0.0f};  // a bulb's radiance, W sr^-1 m^-2
  int emissive = 0;                   // 1: a bulb (no shading)
  glm::vec3 sky_irradiance_up{0.0f};  // the sky's light on an upward surface, W m^-2
  float normal_offset_texels = 0.0f;  // shadow lookups move this many texels along the normal
  int is_ground = 0;                  // 1: the ground plane, shaded at its exact point on the ray
  float ground_height_m = 0.0f;
  int ground_textured = 0;            // 1: the ground's albedo is its texture's (GroundAlbedoBlock)
  float pad0 = 0.0f;                  // the block's size rounds up to a vec4
};
static_assert(offsetof(SurfaceDrawBlock, emissive_radiance) == 0 && offsetof(SurfaceDrawBlock, emissive) == 12 &&
                  offsetof(SurfaceDrawBlock, sky_irradiance_up) == 16 &&
                  offsetof(SurfaceDrawBlock, normal_offset_texels) == 28 && offsetof(SurfaceDrawBlock, is_ground) == 32 &&
                  offsetof(SurfaceDrawBlock, ground_height_m) == 36 && offsetof(SurfaceDrawBlock, ground_textured) == 40 &&
                  sizeof(SurfaceDrawBlock) == 48,
              "SurfaceDrawBlock must follow std140 as surface.frag.glsl declares it");

// lib/ground_albedo.glsl: GroundAlbedoBlock, the scales of the ground's albedo texture.
struct GroundAlbedoBlock {
  glm::vec2 period_m{0.0f};     // the land use's period, the detail's, metres
  float texels = 0.0f;          // texels per side of level 0
  float mean_luminance = 0.0f;  // the texture's mean luminance
};
static_assert(offsetof(GroundAlbedoBlock, period_m) == 0 && offsetof(GroundAlbedoBlock, texels) == 8 &&
                  offsetof(GroundAlbedoBlock, mean_luminance) == 12 && sizeof(GroundAlbedoBlock) == 16,
              "GroundAlbedoBlock must follow std140 as lib/ground_albedo.glsl declares it");

// One member of a block as the GL names it ("Block.member") and its C++ offset: what the contract
// test compares with glGetProgramResourceiv(GL_OFFSET).
struct BlockMember {
  std::string name;
  std::size_t offset;
};
struct BlockLayout {
  const char* block;   // the GLSL block name
  int binding;         // its BLOCK_* binding
  std::size_t size;    // sizeof the C++ struct
  std::vector<BlockMember> members;
};
// Every block of the contract, for tests.
std::vector<BlockLayout> uniform_block_layouts();

// The camera as the shaders see it: the matrices and the per-pixel ray basis of camera.hpp.
CameraBlock camera_block(const Camera& camera);
// The scene's point lights (at most MAX_POINT_LIGHTS, else std::invalid_argument) and sun.
LightsBlock lights_block(const Scene& scene);
// No lights.
LightsBlock no_lights_block();

// size rounded up to GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT (needs a current GL context).
std::size_t aligned_stride(std::size_t size);

// A uniform buffer holding one T (needs a current GL context).
template <class T>
class UniformBuffer {
 public:
  UniformBuffer() : buffer_(make_buffer(sizeof(T), nullptr, GL_DYNAMIC_STORAGE_BIT)) {}
  void update(const T& value) { glNamedBufferSubData(buffer_.id(), 0, sizeof(T), &value); }
  void bind(int binding) const { glBindBufferBase(GL_UNIFORM_BUFFER, static_cast<GLuint>(binding), buffer_.id()); }

 private:
  GlBuffer buffer_;
};

// A uniform buffer holding several T at the GL's offset alignment, bound one at a time as a
// range (a block per cloud). Needs a current GL context.
template <class T>
class UniformArray {
 public:
  void update(const std::vector<T>& values) {
    stride_ = aligned_stride(sizeof(T));
    const std::size_t bytes = stride_ * std::max<std::size_t>(values.size(), 1);
    if (bytes > capacity_) {
      buffer_ = make_buffer(static_cast<GLsizeiptr>(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
      capacity_ = bytes;
    }
    std::vector<unsigned char> packed(bytes, 0);
    for (std::size_t i = 0; i < values.size(); ++i) std::memcpy(packed.data() + i * stride_, &values[i], sizeof(T));
    glNamedBufferSubData(buffer_.id(), 0, static_cast<GLsizeiptr>(bytes), packed.data());
  }
  void bind(int binding, std::size_t index) const {
    glBindBufferRange(GL_UNIFORM_BUFFER, static_cast<GLuint>(binding), buffer_.id(),
                      static_cast<GLintptr>(index * stride_), sizeof(T));
  }

 private:
  GlBuffer buffer_;
  std::size_t capacity_ = 0, stride_ = 0;
};

}  // namespace nimbus::render
