// The GPU light-shaft renderer (shaft_renderer.hpp). Per frame: shadow maps (distance cube maps
// for point lights, an orthographic distance map for the sun), a surface pass (radiance leaving
// each visible surface and its distance), for shadow-volume intervals the skirts built from the
// shadow maps and their nearest/farthest crossing per pixel, and a full-screen shaft pass
// (shaders/shafts.frag.glsl) that adds the airlight by the chosen method.
#include "nimbus/render/shafts/shaft_renderer.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "nimbus/render/core/airlight.hpp"
#include "nimbus/render/core/blue_noise.hpp"
#include "nimbus/render/core/shader_contract.hpp"
#include "nimbus/render/gl/atmosphere_textures.hpp"
#include "nimbus/render/gl/gpu_timer.hpp"
#include "nimbus/render/gl/readback.hpp"
#include "nimbus/render/gl/resources.hpp"
#include "nimbus/render/gl/to_float.hpp"
#include "nimbus/render/gl/uniform_blocks.hpp"
#include "nimbus/render/core/intersect.hpp"
#include "nimbus/render/core/scene_mesh.hpp"
#include "nimbus/render/core/surface_airlight.hpp"
#include "nimbus/render/gl/shader_program.hpp"
#include "nimbus/render/core/metadata.hpp"

namespace nimbus::render {
namespace {

constexpr float kFarDistanceM = 1.0e5f;  // what a shadow map stores where nothing occludes

// A mesh uploaded for drawing with shaders/lib/scene_vertex.glsl.
struct GpuMesh {
  GlBuffer vertices, indices;
  GlVertexArray vao;
  GLsizei count = 0;
};

GpuMesh upload(const SceneMesh& mesh) {
  GpuMesh g;
  g.count = static_cast<GLsizei>(mesh.indices.size());
  g.vao = make_vertex_array();
  if (g.count == 0) return g;
  g.vertices = make_buffer(static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(MeshVertex)), mesh.vertices.data(), 0);
  g.indices = make_buffer(static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(uint32_t)), mesh.indices.data(), 0);
  const GLuint vao = g.vao.id();
  glVertexArrayVertexBuffer(vao, 0, g.vertices.id(), 0, sizeof(MeshVertex));
  glVertexArrayElementBuffer(vao, g.indices.id());
  const GLuint offsets[3] = {offsetof(MeshVertex, position), offsetof(MeshVertex, normal), offsetof(MeshVertex, albedo)};
  for (GLuint a = 0; a < 3; ++a) {
    glEnableVertexArrayAttrib(vao, a);
    glVertexArrayAttribFormat(vao, a, 3, GL_FLOAT, GL_FALSE, offsets[a]);
    glVertexArrayAttribBinding(vao, a, 0);
  }
  check_gl("uploading a scene mesh");
  return g;
}

void draw(const GpuMesh& m) {
  if (m.count == 0) return;
  glBindVertexArray(m.vao.id());
  glDrawElements(GL_TRIANGLES, m.count, GL_UNSIGNED_INT, nullptr);
}

// GL 4.5 table 8.19 face order +X, -X, +Y, -Y, +Z, -Z, with the "up" that makes a face rendered
// through a framebuffer match cube-map sampling.
const std::array<glm::dvec3, 6> kFaceDir = {glm::dvec3(1, 0, 0), glm::dvec3(-1, 0, 0), glm::dvec3(0, 1, 0),
                                            glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1)};
const std::array<glm::dvec3, 6> kFaceUp = {glm::dvec3(0, -1, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1),
                                           glm::dvec3(0, 0, -1), glm::dvec3(0, -1, 0), glm::dvec3(0, -1, 0)};

// The frame's passes as GpuTimer slots. Shafts are timed with the wall clock (glFinish around
// steady_clock) on every device, so their times compare across devices as the benchmark reports.
enum Pass { kShadowMaps = 0, kSurfaces, kShadowVolume, kShafts, kPassCount };

}  // namespace

struct ShaftRenderer::Impl {
  Scene scene;
  ShaftSettings settings;
  GpuMesh occluders, ground;
  std::vector<GpuMesh> bulbs;
  GlVertexArray empty_vao;
  UniformBuffer<CameraBlock> camera_block;
  UniformBuffer<LightsBlock> lights_block;
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
  glm::dvec3 sun_origin{0.0}, sun_axis_x{1, 0, 0}, sun_axis_y{0, 0, 1}, sun_dir{0, -1, 0};
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
  // Skirts end where the airlight behind them is negligible: the march cut-off beyond the
  // farthest the camera can be from a light (the scene's extent).
  double max_skirt_distance_m = 1.0e4;
  void build_skirts();
  void bind_lights(const ShaderProgram& p) const;
  void bind_sky(const ShaderProgram& p) const;
  const ShaderProgram& shaft_program(const ShaftMethod& m);
};

void ShaftRenderer::Impl::build_meshes() {
  Scene occ = scene;
  occ.ground.reset();
  occluders = upload(build_scene_mesh(occ, settings.ground_extent_m));
  if (scene.ground) {
    Scene g;
    g.ground = scene.ground;
    // Under a sky the ground reaches the sky's distance from wherever the camera stands.
    const double extent = scene.sky ? std::max(settings.ground_extent_m, 3.0 * scene.sky->distance_m)
                                    : settings.ground_extent_m;
    ground = upload(build_scene_mesh(g, extent));
  }
  for (const PointLight& l : scene.point_lights) {
    bulbs.push_back(upload(build_bulb_mesh(l)));
  }
  empty_vao = make_vertex_array();
}

void ShaftRenderer::Impl::build_shadow_maps() {
  n_point = static_cast<int>(scene.point_lights.size());
  const int res = settings.point_shadow_res;
  const float clear_far[4] = {kFarDistanceM, 0, 0, 0};
  const float clear_depth = 1.0f;
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  shadow_program.use();
  if (n_point > 0) {
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_CUBE_MAP_ARRAY, 1, &tex);
    point_maps.reset(tex);
    glTextureStorage3D(tex, 1, GL_R32F, res, res, 6 * n_point);
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    point_depth = make_depth_texture(res, res);
    glViewport(0, 0, res, res);
    const glm::dmat4 proj = glm::perspective(M_PI / 2.0, 1.0, 0.01, static_cast<double>(kFarDistanceM));
    shadow_program.set("u_mode", contract::SHADOW_POINT_LIGHT);
    for (int i = 0; i < n_point; ++i) {
      const glm::dvec3 pos = scene.point_lights[static_cast<std::size_t>(i)].position_m;
      shadow_program.set("u_origin", to_float(pos));
      for (int f = 0; f < 6; ++f) {
        const GlFramebuffer fbo = make_framebuffer(
            {{GL_COLOR_ATTACHMENT0, tex, 0, i * 6 + f}, {GL_DEPTH_ATTACHMENT, point_depth.id()}});
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
        glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, clear_far);
        glClearNamedFramebufferfv(fbo.id(), GL_DEPTH, 0, &clear_depth);
        const glm::dmat4 view = glm::lookAt(pos, pos + kFaceDir[static_cast<std::size_t>(f)], kFaceUp[static_cast<std::size_t>(f)]);
        shadow_program.set("u_view_proj", to_float(proj * view));
        draw(occluders);
      }
    }
  }
  if (scene.sun) {
    const int sres = settings.sun_shadow_res;
    sun_dir = -glm::normalize(scene.sun->direction_to_sun);
    glm::dvec3 helper = std::abs(sun_dir.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
    const glm::dvec3 u = glm::normalize(glm::cross(helper, sun_dir));
    const glm::dvec3 v = glm::cross(sun_dir, u);
    // Bounds of the occluders along u, v and the propagation direction.
    glm::dvec3 lo(1e300), hi(-1e300);
    auto extend = [&](const glm::dvec3& p) {
      const glm::dvec3 c(glm::dot(p, u), glm::dot(p, v), glm::dot(p, sun_dir));
      lo = glm::min(lo, c);
      hi = glm::max(hi, c);
    };
    const SceneTracer tracer(scene);  // the occluders' bounding boxes
    for (std::size_t k = 0; k < tracer.occluder_count(); ++k) {
      glm::dvec3 b_lo, b_hi;
      tracer.occluder_bounds(k, b_lo, b_hi);
      for (int c = 0; c < 8; ++c) extend(glm::dvec3(c & 1 ? b_hi.x : b_lo.x, c & 2 ? b_hi.y : b_lo.y, c & 4 ? b_hi.z : b_lo.z));
    }
    if (tracer.occluder_count() == 0) lo = hi = glm::dvec3(0.0);
    const glm::dvec3 pad = 0.01 * (hi - lo) + glm::dvec3(0.5);
    lo -= pad;
    hi += pad;
    sun_origin = lo.x * u + lo.y * v + lo.z * sun_dir;
    sun_axis_x = (hi.x - lo.x) * u;
    sun_axis_y = (hi.y - lo.y) * v;
    sun_texel_m = std::max(hi.x - lo.x, hi.y - lo.y) / sres;
    const double depth = hi.z - lo.z;
    // World -> clip: x, y from the map's axes, z from the distance along the propagation direction.
    glm::dmat4 m(0.0);
    const glm::dvec3 rx = 2.0 * u / (hi.x - lo.x), ry = 2.0 * v / (hi.y - lo.y), rz = 2.0 * sun_dir / depth;
    for (int c = 0; c < 3; ++c) {
      m[c][0] = rx[c];
      m[c][1] = ry[c];
      m[c][2] = rz[c];
    }
    m[3][0] = -glm::dot(rx, sun_origin) - 1.0;
    m[3][1] = -glm::dot(ry, sun_origin) - 1.0;
    m[3][2] = -glm::dot(rz, sun_origin) - 1.0;
    m[3][3] = 1.0;
    sun_view_proj = m;
    sun_map = make_texture_2d(GL_R32F, sres, sres, TextureParams{GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE, 1});
    sun_depth = make_depth_texture(sres, sres);
    const GlFramebuffer fbo = make_framebuffer({{GL_COLOR_ATTACHMENT0, sun_map.id()}, {GL_DEPTH_ATTACHMENT, sun_depth.id()}});
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    glViewport(0, 0, sres, sres);
    glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, clear_far);
    glClearNamedFramebufferfv(fbo.id(), GL_DEPTH, 0, &clear_depth);
    shadow_program.set("u_mode", contract::SHADOW_SUN);
    shadow_program.set("u_origin", to_float(sun_origin));
    shadow_program.set("u_dir", to_float(sun_dir));
    shadow_program.set("u_view_proj", to_float(sun_view_proj));
    draw(occluders);
  }
  check_gl("rendering shadow maps");
  shadow_maps_ready = true;
}

// The shadow volume of each light, from its shadow map (shaders/shadow_volume_build.comp.glsl):
// the skirts are kept in a buffer of their own size and drawn every frame.
void ShaftRenderer::Impl::build_skirts() {
  const int layers = n_point + (scene.sun ? 1 : 0);
  const std::size_t max_quads = settings.max_skirt_quads;
  GlBuffer scratch = make_buffer(static_cast<GLsizeiptr>(max_quads * 6 * sizeof(glm::vec4)), nullptr, GL_DYNAMIC_STORAGE_BIT);
  GlBuffer counter = make_buffer(2 * sizeof(GLuint), nullptr, GL_DYNAMIC_STORAGE_BIT);
  const ShaderProgram& b = skirt_build_program;
  b.use();
  b.set("u_rel_threshold", static_cast<float>(settings.silhouette_jump));
  b.set("u_max_distance", static_cast<float>(max_skirt_distance_m));
  b.set("u_max_quads", static_cast<unsigned>(max_quads));
  if (point_maps) glBindTextureUnit(contract::UNIT_POINT_SHADOW, point_maps.id());
  if (sun_map) glBindTextureUnit(contract::UNIT_SUN_SHADOW, sun_map.id());
  skirts.clear();
  for (int layer = 0; layer < layers; ++layer) {
    const bool is_sun = layer >= n_point;
    const GLuint zero2[2] = {0, 0};
    glNamedBufferSubData(counter.id(), 0, sizeof(zero2), zero2);
    b.set("u_mode", is_sun ? contract::SHADOW_SUN : contract::SHADOW_POINT_LIGHT);
    b.set("u_layer", layer);
    int res = 0;
    if (is_sun) {
      res = settings.sun_shadow_res;
      b.set("u_origin", to_float(sun_origin));
      b.set("u_axis_x", to_float(sun_axis_x));
      b.set("u_axis_y", to_float(sun_axis_y));
      b.set("u_dir", to_float(sun_dir));
    } else {
      res = settings.point_shadow_res;
      b.set("u_origin", to_float(scene.point_lights[static_cast<std::size_t>(layer)].position_m));
    }
    b.set("u_res", res);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, contract::STORAGE_SKIRT_QUADS, scratch.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, contract::STORAGE_SKIRT_COUNTER, counter.id());
    const GLuint groups = static_cast<GLuint>((res + 7) / 8);
    glDispatchCompute(groups, groups, is_sun ? 1u : 6u);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    GLuint got[2] = {0, 0};
    glGetNamedBufferSubData(counter.id(), 0, sizeof(got), got);
    Skirts sk;
    sk.overflow = got[1] != 0;
    sk.count = sk.overflow ? 0 : std::min<std::size_t>(got[0], max_quads);
    sk.vao = make_vertex_array();
    if (sk.count > 0) {
      const auto bytes = static_cast<GLsizeiptr>(sk.count * 6 * sizeof(glm::vec4));
      sk.quads = make_buffer(bytes, nullptr, 0);
      glCopyNamedBufferSubData(scratch.id(), sk.quads.id(), 0, 0, bytes);
      glEnableVertexArrayAttrib(sk.vao.id(), 0);
      glVertexArrayAttribFormat(sk.vao.id(), 0, 4, GL_FLOAT, GL_FALSE, 0);
      glVertexArrayAttribBinding(sk.vao.id(), 0, 0);
      glVertexArrayVertexBuffer(sk.vao.id(), 0, sk.quads.id(), 0, sizeof(glm::vec4));
    }
    skirts.push_back(std::move(sk));
  }
  check_gl("building shadow-volume skirts");
  skirts_ready = true;
}

// The lights (LightsBlock) and the uniforms of shaders/lib/lights.glsl: the shadow maps on
// UNIT_POINT_SHADOW and UNIT_SUN_SHADOW, and the clouds' shadow.
void ShaftRenderer::Impl::bind_lights(const ShaderProgram& p) const {
  lights_block.bind(contract::BLOCK_LIGHTS);
  p.set("u_sun_origin", to_float(sun_origin));
  p.set("u_sun_axis_x", to_float(sun_axis_x));
  p.set("u_sun_axis_y", to_float(sun_axis_y));
  p.set("u_point_shadow_bias", 1.0e-4f);
  p.set("u_sun_shadow_bias", static_cast<float>(1.0e-4 * glm::length(sun_axis_x)));
  p.set("u_point_texel_angle", 2.0f / static_cast<float>(settings.point_shadow_res));
  p.set("u_sun_texel_m", static_cast<float>(sun_texel_m));
  if (point_maps) glBindTextureUnit(contract::UNIT_POINT_SHADOW, point_maps.id());
  if (sun_map) glBindTextureUnit(contract::UNIT_SUN_SHADOW, sun_map.id());
  bind_cloud_shadow(p, cloud_shadow);
}

// The shaft pass's view of the world's end: the sky (shaders/lib/sky.glsl) and the height above
// which nothing shadows the sun.
void ShaftRenderer::Impl::bind_sky(const ShaderProgram& p) const {
  p.set("u_has_sky", scene.sky ? 1 : 0);
  if (scene.sky) {
    p.set("u_sky_zenith", to_float(scene.sky->zenith_radiance_w_sr_m2));
    p.set("u_sky_horizon", to_float(scene.sky->horizon_radiance_w_sr_m2));
    p.set("u_sky_distance", static_cast<float>(scene.sky->distance_m));
  }
  if (atmosphere) {
    bind_sky_view(p, *atmosphere);
  } else {
    p.set("u_sky_physical", 0);
  }
  // With the sun above the horizon nothing shadows the fog above the highest occluder or cloud.
  double ceiling = 1e30;
  if (scene.sun && glm::normalize(scene.sun->direction_to_sun).y > 1e-6)
    ceiling = std::max(opaque_ceiling_m, cloud_shadow ? cloud_shadow->top_y_m : -1e300) + 1e-3;
  p.set("u_shadow_ceiling_m", static_cast<float>(std::clamp(ceiling, -1e30, 1e30)));
}

const ShaderProgram& ShaftRenderer::Impl::shaft_program(const ShaftMethod& m) {
  const int method = shaft_method_code(m.kind);
  const bool table = m.kind == ShaftMethod::Kind::Analytic && m.airlight.kind == AirlightMethod::Table;
  const std::string defines = "#define METHOD " + std::to_string(method) + "\n#define STEPS " +
                              std::to_string(std::max(m.steps, 1)) + "\n#define AIRLIGHT_TABLE " +
                              (table ? "1" : "0") + "\n#define CLOUD_SHADOW " + (cloud_shadow ? "1" : "0") + "\n";
  auto it = shaft_programs.find(defines);
  if (it == shaft_programs.end())
    it = shaft_programs.emplace(defines, ShaderProgram({"fullscreen.vert.glsl", "shafts.frag.glsl"}, defines)).first;
  return it->second;
}

ShaftRenderer::ShaftRenderer(const Scene& scene, const ShaftSettings& settings)
    : impl_(std::make_unique<Impl>(scene, settings)) {
  validate(scene);
  if (scene.point_lights.size() > static_cast<std::size_t>(contract::MAX_POINT_LIGHTS))
    throw std::invalid_argument("scene '" + scene.name + "': the GPU renderer takes at most " +
                                std::to_string(contract::MAX_POINT_LIGHTS) + " point lights, got " +
                                std::to_string(scene.point_lights.size()));
  if (settings.point_shadow_res < 16 || settings.point_shadow_res > 8192)
    throw std::invalid_argument("point_shadow_res must be in [16, 8192]");
  if (settings.sun_shadow_res < 16 || settings.sun_shadow_res > 16384)
    throw std::invalid_argument("sun_shadow_res must be in [16, 16384]");
  const double sigma_t = scene.medium.extinction_per_m;
  impl_->max_skirt_distance_m = sigma_t > 0 ? std::min(1.0e4, 500.0 + 2.0 * settings.march_cutoff_optical / sigma_t) : 1.0e4;
  impl_->build_meshes();
  if (settings.surface_airlight && !scene.point_lights.empty()) {  // for the medium's phase, built once per process (about 2 s), uploaded here
    const SurfaceAirlightTable table(scene.medium.phase);
    impl_->surface_airlight_table = make_texture_2d(GL_R32F, table.nx(), table.ny(),
                                                    TextureParams{GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE, 1});
    glTextureSubImage2D(impl_->surface_airlight_table.id(), 0, 0, 0, table.nx(), table.ny(), GL_RED, GL_FLOAT, table.data());
  }
  impl_->lights_block.update(lights_block(scene));
  if (scene.sky && scene.sky->atmosphere) impl_->atmosphere = upload_atmosphere(scene.sky->atmosphere);
  const SceneTracer tracer(scene);
  for (std::size_t k = 0; k < tracer.occluder_count(); ++k) {
    glm::dvec3 lo, hi;
    tracer.occluder_bounds(k, lo, hi);
    impl_->opaque_ceiling_m = std::max(impl_->opaque_ceiling_m, hi.y);
  }
}

void ShaftRenderer::set_cloud_shadow(const CloudShadowMap* map) { impl_->cloud_shadow = map; }
GLuint ShaftRenderer::color_texture() const { return impl_->out.id(); }
GLuint ShaftRenderer::distance_texture() const { return impl_->distance.id(); }

ShaftRenderer::~ShaftRenderer() = default;

Image ShaftRenderer::render(const Camera& camera, const ShaftMethod& method, ShaftFrameStats* stats) {
  validate(camera);
  Impl& s = *impl_;
  if (method.kind == ShaftMethod::Kind::Reference)
    throw std::invalid_argument("method 'reference' is the CPU renderer (render_reference), not the GPU one");
  if (method.kind == ShaftMethod::Kind::Analytic && method.airlight.kind == AirlightMethod::Table &&
      s.scene.medium.phase.kind != PhaseKind::Isotropic)
    throw std::invalid_argument("method '" + to_string(method) + "': Sun et al.'s F table covers the isotropic phase only; this scene's phase is " +
                                to_string(s.scene.medium.phase) + " (use analytic:stable)");
  ShaftFrameStats st;
  const int w = camera.width, h = camera.height;
  GpuTimer timer(kPassCount, stats != nullptr, GpuTimer::Clock::Wall);
  if (!s.shadow_maps_ready) timer.time(kShadowMaps, [&] { s.build_shadow_maps(); });

  // Surface pass.
  if (s.target_w != w || s.target_h != h) {
    const TextureParams nearest{GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE, 1};
    s.radiance = make_texture_2d(GL_RGBA32F, w, h, nearest);
    s.distance = make_texture_2d(GL_R32F, w, h, nearest);
    s.depth_target = make_depth_texture(w, h);
    s.surface_fbo = make_framebuffer({{GL_COLOR_ATTACHMENT0, s.radiance.id()},
                                      {GL_COLOR_ATTACHMENT1, s.distance.id()},
                                      {GL_DEPTH_ATTACHMENT, s.depth_target.id()}});
    s.out = make_texture_2d(GL_RGBA32F, w, h, nearest);
    s.out_fbo = make_framebuffer({{GL_COLOR_ATTACHMENT0, s.out.id()}});
    s.target_w = w;
    s.target_h = h;
  }
  const GlTexture& radiance = s.radiance;
  const GlTexture& distance = s.distance;
  const GlFramebuffer& surface_fbo = s.surface_fbo;
  const CameraBlock camera_values = camera_block(camera);
  const glm::mat4 view_proj = camera_values.view_proj;
  s.camera_block.update(camera_values);
  s.camera_block.bind(contract::BLOCK_CAMERA);
  const float sigma_t = static_cast<float>(s.scene.medium.extinction_per_m);
  const float sigma_s = static_cast<float>(s.scene.medium.scattering_per_m());
  timer.time(kSurfaces, [&] {
    glBindFramebuffer(GL_FRAMEBUFFER, surface_fbo.id());
    glViewport(0, 0, w, h);
    const float zero[4] = {0, 0, 0, 0};
    const float one = 1.0f;
    glClearNamedFramebufferfv(surface_fbo.id(), GL_COLOR, 0, zero);
    glClearNamedFramebufferfv(surface_fbo.id(), GL_COLOR, 1, zero);
    glClearNamedFramebufferfv(surface_fbo.id(), GL_DEPTH, 0, &one);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    const bool clouds = s.cloud_shadow != nullptr;
    const bool airlight = s.settings.surface_airlight && !s.scene.point_lights.empty();  // the sun adds none
    auto it = s.surface_programs.find({clouds, airlight});
    if (it == s.surface_programs.end())
      it = s.surface_programs
               .emplace(std::make_pair(clouds, airlight),
                        ShaderProgram({"surface.vert.glsl", "surface.frag.glsl"},
                                      std::string("#define CLOUD_SHADOW ") + (clouds ? "1" : "0") +
                                          "\n#define SURFACE_AIRLIGHT " + (airlight ? "1" : "0") + "\n"))
               .first;
    const ShaderProgram& p = it->second;
    p.use();
    p.set("u_view_proj", view_proj);
    p.set("u_sigma_t", sigma_t);
    if (airlight) {
      p.set("u_sigma_s", sigma_s);
      glBindTextureUnit(contract::UNIT_SURFACE_AIRLIGHT, s.surface_airlight_table.id());
    }
    s.bind_lights(p);
    p.set("u_emissive", 0);
    p.set("u_sky_irradiance_up", s.scene.sky ? to_float(sky_irradiance(*s.scene.sky, glm::dvec3(0, 1, 0))) : glm::vec3(0.0f));
    p.set("u_normal_offset_texels", 0.0f);  // the ground is in no shadow map: no acne to avoid
    draw(s.ground);
    p.set("u_normal_offset_texels", 1.5f);
    draw(s.occluders);
    p.set("u_emissive", 1);
    for (std::size_t i = 0; i < s.bulbs.size(); ++i) {
      const PointLight& l = s.scene.point_lights[i];
      p.set("u_emissive_radiance", to_float(l.intensity_w_sr / (M_PI * l.bulb_radius_m * l.bulb_radius_m)));
      draw(s.bulbs[i]);
    }
    check_gl("surface pass");
  });

  // Shadow-volume intervals: skirts from each light's map, nearest/farthest crossing per pixel.
  const int layers = s.n_point + (s.scene.sun ? 1 : 0);
  GlTexture sv_near, sv_far;
  if (method.kind == ShaftMethod::Kind::ShadowVolume) {
    GLuint ids[2] = {0, 0};
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 2, ids);
    sv_near.reset(ids[0]);
    sv_far.reset(ids[1]);
    for (GLuint id : ids) {
      glTextureStorage3D(id, 1, GL_R32F, w, h, std::max(layers, 1));
      glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    if (!s.skirts_ready) timer.time(kShadowMaps, [&] { s.build_skirts(); });
    timer.time(kShadowVolume, [&] {
      for (int layer = 0; layer < layers; ++layer) {
        const Impl::Skirts& sk = s.skirts[static_cast<std::size_t>(layer)];
        const std::size_t n_quads = sk.count;
        st.skirt_quads += n_quads;
        st.skirt_overflow = st.skirt_overflow || sk.overflow;
        const GlFramebuffer fbo = make_framebuffer(
            {{GL_COLOR_ATTACHMENT0, sv_near.id(), 0, layer}, {GL_COLOR_ATTACHMENT1, sv_far.id(), 0, layer}});
        const float near_clear[4] = {3.0e38f, 0, 0, 0};
        const float far_clear[4] = {0, 0, 0, 0};
        glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, near_clear);
        glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 1, far_clear);
        if (sk.overflow) {
          // Too many skirts: mark the whole ray ambiguous (sampled), which is always correct.
          const float zero[4] = {0, 0, 0, 0};
          const float huge[4] = {1.0e30f, 0, 0, 0};
          glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, zero);
          glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 1, huge);
          continue;
        }
        if (n_quads == 0) continue;
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
        glViewport(0, 0, w, h);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        glEnablei(GL_BLEND, 0);
        glEnablei(GL_BLEND, 1);
        glBlendEquationi(0, GL_MIN);
        glBlendEquationi(1, GL_MAX);
        glBlendFunci(0, GL_ONE, GL_ONE);
        glBlendFunci(1, GL_ONE, GL_ONE);
        const ShaderProgram& iv = s.skirt_interval_program;
        iv.use();
        glBindTextureUnit(contract::UNIT_SCENE_DISTANCE, distance.id());
        glBindVertexArray(sk.vao.id());
        glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(n_quads * 6));
        glDisablei(GL_BLEND, 0);
        glDisablei(GL_BLEND, 1);
        glBlendEquation(GL_FUNC_ADD);
      }
      check_gl("shadow-volume intervals");
    });
  }

  // Shaft pass.
  if (!s.jitter_tex) {
    const int n = 64;
    const std::vector<float> tile = blue_noise_tile(n, s.settings.jitter_seed);
    s.jitter_tex = make_texture_2d(GL_R32F, n, n, TextureParams{GL_NEAREST, GL_NEAREST, GL_REPEAT, 1});
    glTextureSubImage2D(s.jitter_tex.id(), 0, 0, 0, n, n, GL_RED, GL_FLOAT, tile.data());
  }
  const GlFramebuffer& out_fbo = s.out_fbo;
  const ShaderProgram& p = s.shaft_program(method);
  timer.time(kShafts, [&] {
    glBindFramebuffer(GL_FRAMEBUFFER, out_fbo.id());
    glViewport(0, 0, w, h);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    p.use();
    s.bind_lights(p);
    s.bind_sky(p);
    p.set("u_sigma_t", sigma_t);
    p.set("u_sigma_s", sigma_s);
    p.set("u_phase_kind", phase_code(s.scene.medium.phase.kind));
    p.set("u_phase_g", static_cast<float>(s.scene.medium.phase.g));
    p.set("u_march_cutoff_m",
          static_cast<float>(sigma_t > 0 ? std::min(s.settings.march_cutoff_optical / sigma_t, camera.far_m) : camera.far_m));
    p.set("u_jitter_mode", jitter_code(method.jitter));
    glBindTextureUnit(contract::UNIT_SURFACE_RADIANCE, radiance.id());
    glBindTextureUnit(contract::UNIT_SCENE_DISTANCE, distance.id());
    glBindTextureUnit(contract::UNIT_JITTER, s.jitter_tex.id());
    if (method.kind == ShaftMethod::Kind::ShadowVolume) {
      glBindTextureUnit(contract::UNIT_SV_NEAR, sv_near.id());
      glBindTextureUnit(contract::UNIT_SV_FAR, sv_far.id());
    }
    if (method.kind == ShaftMethod::Kind::Analytic && method.airlight.kind == AirlightMethod::Table) {
      auto it = s.f_tables.find(method.airlight.n);
      if (it == s.f_tables.end()) {
        const FTable table(method.airlight.n);
        const int n = table.size();
        GlTexture t = make_texture_2d(GL_R32F, n, n, TextureParams{GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE, 1});
        glTextureSubImage2D(t.id(), 0, 0, 0, n, n, GL_RED, GL_FLOAT, table.data());
        it = s.f_tables.emplace(n, std::move(t)).first;
      }
      p.set("u_F_size", method.airlight.n);
      glBindTextureUnit(contract::UNIT_F_TABLE, it->second.id());
    }
    draw_fullscreen_triangle(s.empty_vao);
    check_gl("shaft pass");
  });
  Image img = read_rgba(out_fbo, w, h);
  timer.finish();
  st.shadow_maps_ms = timer.ms(kShadowMaps);
  st.surfaces_ms = timer.ms(kSurfaces);
  st.shadow_volume_ms = timer.ms(kShadowVolume);
  st.shafts_ms = timer.ms(kShafts);
  st.total_ms = timer.total_ms();
  st.timing = timer.method();
  for (float& v : img.rgba)
    if (!std::isfinite(v)) throw std::runtime_error("GPU renderer produced a non-finite pixel value (method " + to_string(method) + ")");
  describe_frame(img, s.scene, camera, to_string(method));
  if (method.kind != ShaftMethod::Kind::Analytic) {
    img.metadata["samples_per_ray"] = std::to_string(method.steps) +
                                      (method.kind == ShaftMethod::Kind::ShadowVolume ? " (in [tn, tf] only)" : "");
    img.metadata["jitter"] = to_string(method.jitter);
  }
  img.metadata["surface_airlight"] = s.settings.surface_airlight ? "on" : "off";
  img.metadata["shadow_map_res"] = std::to_string(s.settings.point_shadow_res) + " per cube face, sun " +
                                   std::to_string(s.settings.sun_shadow_res);
  if (stats) *stats = st;
  return img;
}

}  // namespace nimbus::render
