// The GPU light-shaft renderer's state (shaft_renderer.hpp): the scene's meshes, the lights'
// shadow maps and shadow-volume skirts, the programs and the frame's targets. Private to
// render/shafts/src/shaft_*.cpp.
#pragma once
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "nimbus/render/scene/scene_mesh.hpp"
#include "nimbus/render/gl/atmosphere_textures.hpp"
#include "nimbus/render/gl/gpu_timer.hpp"
#include "nimbus/render/gl/resources.hpp"
#include "nimbus/render/gl/shader_program.hpp"
#include "nimbus/render/gl/uniform_blocks.hpp"
#include "nimbus/render/shafts/shaft_renderer.hpp"

namespace nimbus::render {
namespace shaft_detail {

constexpr float kFarDistanceM = 1.0e5f;  // what a shadow map stores where nothing occludes
constexpr double kHorizonGroundM = 2.0e6;  // half-size of the ground quad under a sky

// A mesh uploaded for drawing with shaders/lib/scene_vertex.glsl.
struct GpuMesh {
  GlBuffer vertices, indices;
  GlVertexArray vao;
  GLsizei count = 0;
};

GpuMesh upload(const SceneMesh& mesh);
void draw(const GpuMesh& m);

// The frame's passes as GpuTimer slots. Shafts are timed with the wall clock (glFinish around
// steady_clock) on every device, so their times compare across devices as the benchmark reports.
enum Pass { kShadowMaps = 0, kSurfaces, kShadowVolume, kShafts, kPassCount };

class ShaftMethodPass;

}  // namespace shaft_detail

struct ShaftRenderer::Impl {
  Scene scene;
  ShaftSettings settings;
  unsigned jitter_frame = 0;  // set_jitter_frame
  shaft_detail::GpuMesh occluders, ground;
  GlTexture ground_albedo;  // the ground's albedo texture (ground_albedo.hpp), when it has one
  std::vector<shaft_detail::GpuMesh> bulbs;
  GlVertexArray empty_vao;
  UniformBuffer<CameraBlock> camera_block;
  UniformBuffer<LightsBlock> lights_block;
  mutable UniformBuffer<SceneShadowsBlock> shadows_block;  // filled as it is bound (bind_lights)
  mutable UniformBuffer<SkyBlock> sky_ubo;                  // filled as it is bound (bind_sky)
  UniformBuffer<ShaftPassBlock> shaft_pass_ubo;
  UniformBuffer<SurfaceDrawBlock> surface_draw_ubo;
  UniformBuffer<GroundAlbedoBlock> ground_albedo_ubo;
  ShaderProgram shadow_program{{"shadow_distance.vert.glsl", "shadow_distance.frag.glsl"}};
  std::map<std::pair<bool, bool>, ShaderProgram> surface_programs;  // by (CLOUD_SHADOW, SURFACE_AIRLIGHT)
  ShaderProgram skirt_build_program{{"shadow_volume_build.comp.glsl"}};
  ShaderProgram skirt_interval_program{{"shadow_volume_interval.vert.glsl", "shadow_volume_interval.frag.glsl"}};
  std::map<std::string, ShaderProgram> shaft_programs;

  // Shadow maps.
  int n_point = 0;
  GlTexture point_maps;  // cube map array, R32F, 6 layers per light
  GlTexture point_depth;
  GlTexture sun_map;
  GlTexture sun_depth;
  glm::dvec3 sun_origin{0.0}, sun_axis_x{1, 0, 0}, sun_axis_y{0, 0, 1};
  glm::dvec3 sun_propagation{0, -1, 0};  // -direction_to_sun: the sun map's depth axis
  glm::dmat4 sun_view_proj{1.0};
  double sun_texel_m = 1.0;
  bool shadow_maps_ready = false;

  // Shadow-volume skirts per light (point lights, then the sun), built once from the maps.
  struct Skirts {
    GlBuffer quads;  // 6 vec4 vertices per quad, metres
    GlVertexArray vao;
    std::size_t count = 0;
    bool overflow = false;
  };
  std::vector<Skirts> skirts;
  bool skirts_ready = false;

  // Jitter and the F table.
  GlTexture jitter_tex;
  std::optional<AtmosphereTextures> atmosphere;  // the physical sky's tables, when the scene's sky has them
  const CloudShadowMap* cloud_shadow = nullptr;
  double opaque_ceiling_m = -1e300;  // top of the occluders (world y)
  // The frame's render targets, kept while the image size stays the same.
  int target_w = 0, target_h = 0;
  GlTexture radiance, distance, depth_target, out;
  GlFramebuffer surface_fbo, out_fbo;
  std::map<int, GlTexture> f_tables;
  GlTexture surface_airlight_table;  // g(ln Tsp, theta_s), R32F, when settings.surface_airlight

  Impl(const Scene& s, const ShaftSettings& st) : scene(s), settings(st) {}

  void build_meshes();
  void build_shadow_maps();
  void build_point_maps();
  void build_sun_map();
  // Skirts end where the airlight behind them is negligible: the march cut-off beyond the
  // farthest the camera can be from a light (the scene's extent).
  double max_skirt_distance_m = 1.0e4;
  void build_skirts();
  void bind_lights(const ShaderProgram& p) const;
  void bind_sky() const;
  ShaftPassBlock shaft_pass_block(const Camera& camera, const ShaftMethod& method) const;
  const ShaderProgram& shaft_program(const ShaftMethod& m);
  // The frame's targets for a w x h image (kept while the size stays the same).
  void ensure_targets(int w, int h);
  // The surface pass: radiance leaving each visible surface, and its distance.
  void draw_surfaces(const CameraBlock& camera, int w, int h);
  // Its program by (clouds' shadow, surface airlight); the airlight off without point lights (the sun adds none).
  const ShaderProgram& surface_program();
  bool surface_airlight_on() const { return settings.surface_airlight && !scene.lamps.empty(); }
  // The shaft pass: the airlight added along each pixel's ray by the method's program p, over the surfaces.
  void ensure_jitter();
  void draw_shafts(const Camera& camera, const ShaderProgram& p, const shaft_detail::ShaftMethodPass& method_pass);
};

}  // namespace nimbus::render
