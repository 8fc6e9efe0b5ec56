// The half-angle slice renderer's state (cloud_renderer.hpp): the clouds' textures and hulls, the
// compiled programs, the uniform blocks and the light, eye and pass buffers. Private to
// render/clouds/src/cloud_*.cpp.
#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <tuple>
#include <vector>

#include "cloud_slice_geometry.hpp"
#include "nimbus/render/clouds/cloud_renderer.hpp"
#include "nimbus/render/gl/atmosphere_textures.hpp"
#include "nimbus/render/gl/gpu_timer.hpp"
#include "nimbus/render/gl/resources.hpp"
#include "nimbus/render/gl/shader_program.hpp"
#include "nimbus/render/gl/uniform_blocks.hpp"

namespace nimbus::render {
namespace cloud_detail {

constexpr int kJitterTile = 64;        // blue-noise tile side, pixels (power of two)
constexpr std::uint32_t kJitterSeed = 5;

// The frame's passes as GpuTimer slots.
enum Pass { kLight = 0, kEye, kComposite, kPassCount };

// Where set_clouds put a cloud; set_motion moves it from here.
struct Placement {
  glm::dmat4 index_to_world{1.0};
  openvdb::math::Transform::Ptr transform;
  glm::dvec3 world_min{0.0}, world_max{0.0};
  glm::dmat4 world_to_texture{1.0};
  ConvexHull hull;
  std::vector<glm::dvec3> hull_vertices;
};

}  // namespace cloud_detail

struct CloudRenderer::Impl {
  std::vector<CloudVolume> clouds;         // as drawn (moved)
  std::vector<VolumeTexture> textures;
  std::vector<std::optional<VolumeTexture>> next_textures;  // the next keyframe, if any
  std::vector<cloud_detail::Placement> placements;
  std::vector<cloud_detail::ConvexHull> hulls;           // where each cloud's density can be non-zero
  std::vector<glm::dvec3> hull_points;     // all their vertices
  std::vector<std::vector<glm::dvec3>> cloud_hull_points;  // each hull's vertices
  ShaderProgram light_program{{"cloud_light.vert.glsl", "cloud_light.frag.glsl"}, "#define LAMP 0\n"};
  ShaderProgram lamp_light_program{{"cloud_light.vert.glsl", "cloud_light.frag.glsl"}, "#define LAMP 1\n"};
  ShaderProgram blur_program{{"fullscreen.vert.glsl", "cloud_light_blur.frag.glsl"}};
  std::optional<ShaderProgram> accumulate_program;  // the second light's pass on
  std::optional<ShaderProgram> under_programs[2];    // the far copies' pass, [underlay]
  const ShaderProgram& under_program(bool underlay);
  std::map<std::tuple<bool, int, int, bool>, ShaderProgram> eye_programs;  // by (underlay, octaves, MS_VOLUME, lamp)
  std::optional<ShaderProgram> composite_programs[2];  // [spots]: without and with spots in the scene
  const ShaderProgram& composite_program_for(bool spots);
  std::optional<AtmosphereTextures> aerial;  // the underlay scene's physical sky, uploaded once per table set
  UniformBuffer<CameraBlock> camera_ubo;
  UniformBuffer<LightsBlock> lights_ubo;
  UniformBuffer<SkyBlock> sky_ubo;
  mutable UniformBuffer<LightVolumeBlock> light_volume_ubo;  // filled as it is bound (bind_light_volume_grid)
  UniformArray<CloudBlock> cloud_ubo;  // one block per cloud, refilled every frame
  UniformBuffer<SliceLightBlock> slice_light_ubo;  // the light of the pass being drawn
  GlVertexArray empty_vao, mesh_vao;
  GlBuffer mesh_buffer;
  std::size_t mesh_capacity = 0;  // vertices
  GlTexture jitter;

  int light_res = 0;
  GlTexture light_tex[2];
  GlFramebuffer light_fbo[2];

  int eye_w = 0, eye_h = 0;
  bool eye_has_distance = false;
  GlTexture eye_color, eye_distance, out_color, out_depth;  // out_depth: RG32F (distance, cloud alpha)
  GlFramebuffer eye_fbo, out_fbo;
  // The second light's pass on draws here, then adds its radiance into eye_color.
  int pass_w = 0, pass_h = 0;
  GlTexture pass_color, pass_distance;
  GlFramebuffer pass_fbo;

  // The light volume (set_light_volume): fluence, flux and second moment side by side along x.
  GlTexture light_volume_tex;
  glm::dvec3 lv_world_min{0.0};
  glm::dvec3 lv_cell_m{0.0};
  glm::dvec3 lv_light_dir{0.0, -1.0, 0.0};
  glm::ivec3 lv_cells{0};
  // The light volume's radiance toward this frame's eye at its cell centres, for clouds of phase
  // lr_phase (make_light_radiance; lib/cloud_light_volume.glsl's light_volume_radiance).
  GlTexture light_radiance_tex;
  // The same for the near pass's copies of periodic tiles (cloud_tiles.hpp): copy i's texture is
  // made toward the eye moved back by its offset, on the clouds' own grid.
  std::vector<GlTexture> copy_radiance_tex;
  glm::ivec3 lr_cells{0};
  std::optional<ShaderProgram> radiance_program;
  void make_light_radiance(const glm::dvec3& eye, const glm::vec3& phase, GlTexture& target);

  // ms_volume: MS_VOLUME of cloud_slice.frag.glsl (0 none, 1 per sample, 2 the frame's radiance).
  const ShaderProgram& eye_program(bool underlay, int octaves, int ms_volume, bool lamp);
  // The light volume's uniforms (u_lv_*) on a program that reads it.
  void bind_light_volume_grid() const;  // LightVolumeBlock: the grid's corner, cells, light
  void upload_mesh(const cloud_detail::SliceMesh& mesh);
  void ensure_light_buffers(int res);
  void ensure_eye_buffers(int w, int h, bool distance);
  void ensure_pass_buffers(int w, int h);
  // Buffers and programs for a frame of w x h with `passes` lights (and an underlay or not).
  void prepare_frame(int w, int h, const CloudSliceSettings& settings, std::size_t passes, bool underlay);
  // The clouds (and the fog in front of them) over the underlay's scene, read back, with what
  // each pixel shows when `depths` is given.
  Image composite(const SceneUnderlay& underlay, GpuTimer& timer, int w, int h, PixelDepths* depths);
};

}  // namespace nimbus::render
