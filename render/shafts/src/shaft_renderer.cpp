// The GPU light-shaft renderer (shaft_renderer.hpp). Per frame: shadow maps, built once
// (shaft_shadow_maps.cpp: distance cube maps for point lights, an orthographic distance map for the
// sun), a surface pass (radiance leaving each visible surface and its distance), the method's own
// work (shaft_method_pass.cpp: for shadow-volume intervals the skirts' nearest/farthest crossing per
// pixel), and a full-screen shaft pass (shaders/shafts.frag.glsl) that adds the airlight.
#include "nimbus/render/shafts/shaft_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "nimbus/render/core/blue_noise.hpp"
#include "nimbus/render/scene/intersect.hpp"
#include "nimbus/render/scene/metadata.hpp"
#include "nimbus/render/core/shader_contract.hpp"
#include "nimbus/render/media/surface_airlight.hpp"
#include "nimbus/render/gl/readback.hpp"
#include "nimbus/render/gl/to_float.hpp"
#include "shaft_method_pass.hpp"
#include "shaft_renderer_impl.hpp"

namespace nimbus::render {

using namespace shaft_detail;

// The lights (LightsBlock) and shaders/lib/lights.glsl's shadow maps: their geometry
// (SceneShadowsBlock), the maps on UNIT_POINT_SHADOW and UNIT_SUN_SHADOW, and the clouds' shadow.
void ShaftRenderer::Impl::bind_lights(const ShaderProgram& p) const {
  lights_block.bind(contract::BLOCK_LIGHTS);
  SceneShadowsBlock shadows;
  shadows.sun_origin = to_float(sun_origin);
  shadows.sun_axis_x = to_float(sun_axis_x);
  shadows.sun_axis_y = to_float(sun_axis_y);
  shadows.point_bias = 1.0e-4f;
  shadows.sun_bias = static_cast<float>(1.0e-4 * glm::length(sun_axis_x));
  shadows.point_texel_angle = 2.0f / static_cast<float>(settings.point_shadow_res);
  shadows.sun_texel_m = static_cast<float>(sun_texel_m);
  shadows_block.update(shadows);
  shadows_block.bind(contract::BLOCK_SCENE_SHADOWS);
  if (point_maps) glBindTextureUnit(contract::UNIT_POINT_SHADOW, point_maps.id());
  if (sun_map) glBindTextureUnit(contract::UNIT_SUN_SHADOW, sun_map.id());
  bind_cloud_shadow(p, cloud_shadow);
}

// The shaft pass's view of the world's end: the sky (shaders/lib/sky.glsl).
void ShaftRenderer::Impl::bind_sky() const {
  sky_ubo.update(sky_block(scene.sky ? &*scene.sky : nullptr, atmosphere ? &*atmosphere : nullptr));
  sky_ubo.bind(contract::BLOCK_SKY);
  if (atmosphere) bind_atmosphere_textures(*atmosphere);
}

// The shaft pass's own values: where its march ends, the height above which nothing shadows the
// sun, its jitter, and the analytic method's F table.
ShaftPassBlock ShaftRenderer::Impl::shaft_pass_block(const Camera& camera, const ShaftMethod& method) const {
  ShaftPassBlock b;
  const double sigma_t = scene.medium.extinction_per_m;
  b.march_cutoff_m =
      static_cast<float>(sigma_t > 0 ? std::min(settings.march_cutoff_optical / sigma_t, camera.far_m) : camera.far_m);
  // With the sun above the horizon nothing shadows the fog above the highest occluder or cloud.
  double ceiling = 1e30;
  if (scene.sun && glm::normalize(scene.sun->direction_to_sun).y > 1e-6)
    ceiling = std::max(opaque_ceiling_m, cloud_shadow ? cloud_shadow->top_y_m : -1e300) + 1e-3;
  b.shadow_ceiling_m = static_cast<float>(std::clamp(ceiling, -1e30, 1e30));
  b.jitter_mode = jitter_code(method.jitter);
  const double shift = jitter_frame * 0.6180339887498949;
  b.jitter_shift = static_cast<float>(shift - std::floor(shift));
  b.f_table_size = method.airlight.n;
  return b;
}

const ShaderProgram& ShaftRenderer::Impl::shaft_program(const ShaftMethod& m) {
  const int method = shaft_method_code(m.kind);
  const bool table = m.kind == ShaftMethod::Kind::Analytic && m.airlight.kind == AirlightMethod::Table;
  const std::string defines = "#define METHOD " + std::to_string(method) + "\n#define STEPS " +
                              std::to_string(std::max(m.steps, 1)) + "\n#define AIRLIGHT_TABLE " +
                              (table ? "1" : "0") + "\n#define CLOUD_SHADOW " + (cloud_shadow ? "1" : "0") +
                              "\n#define SPOTS " + (any_spot(scene.lamps) ? "1" : "0") + "\n";
  auto it = shaft_programs.find(defines);
  if (it == shaft_programs.end())
    it = shaft_programs.emplace(defines, ShaderProgram({"fullscreen.vert.glsl", "shafts.frag.glsl"}, defines)).first;
  return it->second;
}

ShaftRenderer::ShaftRenderer(const Scene& scene, const ShaftSettings& settings)
    : impl_(std::make_unique<Impl>(scene, settings)) {
  validate(scene);
  if (scene.lamps.size() > static_cast<std::size_t>(contract::MAX_POINT_LIGHTS))
    throw std::invalid_argument("scene '" + scene.name + "': the GPU renderer takes at most " +
                                std::to_string(contract::MAX_POINT_LIGHTS) + " point lights, got " +
                                std::to_string(scene.lamps.size()));
  if (settings.point_shadow_res < 16 || settings.point_shadow_res > 8192)
    throw std::invalid_argument("point_shadow_res must be in [16, 8192]");
  if (settings.sun_shadow_res < 16 || settings.sun_shadow_res > 16384)
    throw std::invalid_argument("sun_shadow_res must be in [16, 16384]");
  const double sigma_t = scene.medium.extinction_per_m;
  impl_->max_skirt_distance_m = sigma_t > 0 ? std::min(1.0e4, 500.0 + 2.0 * settings.march_cutoff_optical / sigma_t) : 1.0e4;
  impl_->build_meshes();
  if (settings.surface_airlight && !scene.lamps.empty()) {  // for the medium's phase, built once per process (about 2 s), uploaded here
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
void ShaftRenderer::set_jitter_frame(unsigned frame) { impl_->jitter_frame = frame; }
GLuint ShaftRenderer::color_texture() const { return impl_->out.id(); }
GLuint ShaftRenderer::distance_texture() const { return impl_->distance.id(); }

ShaftRenderer::~ShaftRenderer() = default;

void ShaftRenderer::Impl::ensure_targets(int w, int h) {
  if (target_w == w && target_h == h) return;
  const TextureParams nearest{GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE, 1};
  radiance = make_texture_2d(GL_RGBA32F, w, h, nearest);
  distance = make_texture_2d(GL_R32F, w, h, nearest);
  depth_target = make_depth_texture(w, h);
  surface_fbo = make_framebuffer({{GL_COLOR_ATTACHMENT0, radiance.id()},
                                  {GL_COLOR_ATTACHMENT1, distance.id()},
                                  {GL_DEPTH_ATTACHMENT, depth_target.id()}});
  out = make_texture_2d(GL_RGBA32F, w, h, nearest);
  out_fbo = make_framebuffer({{GL_COLOR_ATTACHMENT0, out.id()}});
  target_w = w;
  target_h = h;
}

const ShaderProgram& ShaftRenderer::Impl::surface_program() {
  const bool clouds = cloud_shadow != nullptr;
  const bool airlight = surface_airlight_on();
  auto it = surface_programs.find({clouds, airlight});
  if (it == surface_programs.end())
    it = surface_programs
             .emplace(std::make_pair(clouds, airlight),
                      ShaderProgram({"surface.vert.glsl", "surface.frag.glsl"},
                                    std::string("#define CLOUD_SHADOW ") + (clouds ? "1" : "0") +
                                        "\n#define SURFACE_AIRLIGHT " + (airlight ? "1" : "0") +
                                        "\n#define SPOTS " + (any_spot(scene.lamps) ? "1" : "0") + "\n"))
             .first;
  return it->second;
}

void ShaftRenderer::Impl::draw_surfaces(const CameraBlock& camera, int w, int h) {
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
  const ShaderProgram& p = surface_program();
  p.use();
  p.set("u_view_proj", camera.view_proj);
  p.set("u_sigma_t", static_cast<float>(scene.medium.extinction_per_m));
  if (surface_airlight_on()) {
    p.set("u_sigma_s", static_cast<float>(scene.medium.scattering_per_m()));
    glBindTextureUnit(contract::UNIT_SURFACE_AIRLIGHT, surface_airlight_table.id());
  }
  bind_lights(p);
  // The ground: its point on each pixel's ray (exact at any distance, where the huge quad's
  // interpolated position is not), and its albedo texture when it has one.
  SurfaceDrawBlock d;
  d.sky_irradiance_up = scene.sky ? to_float(sky_irradiance(*scene.sky, glm::dvec3(0, 1, 0))) : glm::vec3(0.0f);
  d.normal_offset_texels = 0.0f;  // the ground is in no shadow map: no acne to avoid
  d.is_ground = 1;
  d.ground_height_m = static_cast<float>(scene.ground ? scene.ground->height_m : 0.0);
  const GroundAlbedoTexture* tex = scene.ground ? scene.ground->albedo_texture.get() : nullptr;
  d.ground_textured = tex ? 1 : 0;
  surface_draw_ubo.update(d);
  surface_draw_ubo.bind(contract::BLOCK_SURFACE_DRAW);
  if (tex) {
    glBindTextureUnit(contract::UNIT_GROUND_ALBEDO, ground_albedo.id());
    GroundAlbedoBlock g;
    g.period_m = glm::vec2(static_cast<float>(tex->params.period_m), static_cast<float>(tex->params.detail_period_m));
    g.texels = static_cast<float>(tex->params.size);
    g.mean_luminance = static_cast<float>(tex->mean_luminance);
    ground_albedo_ubo.update(g);
    ground_albedo_ubo.bind(contract::BLOCK_GROUND_ALBEDO);
  }
  // Under a sky the ground is drawn first with depth clamping: beyond the far plane (toward the
  // horizon) it lies at depth 1 instead of being clipped, and LEQUAL lets it pass the cleared depth.
  if (scene.sky) {
    glEnable(GL_DEPTH_CLAMP);
    glDepthFunc(GL_LEQUAL);
  }
  draw(ground);
  glDisable(GL_DEPTH_CLAMP);
  glDepthFunc(GL_LESS);
  d.is_ground = 0;
  d.normal_offset_texels = 1.5f;
  surface_draw_ubo.update(d);
  draw(occluders);
  d.emissive = 1;
  for (std::size_t i = 0; i < bulbs.size(); ++i) {
    const Light& l = scene.lamps[i];
    d.emissive_radiance = to_float(l.intensity_w_sr / (M_PI * l.bulb_radius_m * l.bulb_radius_m));
    surface_draw_ubo.update(d);
    draw(bulbs[i]);
  }
  check_gl("surface pass");
}

void ShaftRenderer::Impl::ensure_jitter() {
  if (jitter_tex) return;
  const int n = 64;
  const std::vector<float> tile = blue_noise_tile(n, settings.jitter_seed);
  jitter_tex = make_texture_2d(GL_R32F, n, n, TextureParams{GL_NEAREST, GL_NEAREST, GL_REPEAT, 1});
  glTextureSubImage2D(jitter_tex.id(), 0, 0, 0, n, n, GL_RED, GL_FLOAT, tile.data());
}

void ShaftRenderer::Impl::draw_shafts(const Camera& camera, const ShaderProgram& p, const ShaftMethodPass& method_pass) {
  const ShaftMethod& method = method_pass.method();
  const double sigma_t = scene.medium.extinction_per_m;
  glBindFramebuffer(GL_FRAMEBUFFER, out_fbo.id());
  glViewport(0, 0, camera.width, camera.height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  p.use();
  bind_lights(p);
  bind_sky();
  shaft_pass_ubo.update(shaft_pass_block(camera, method));
  shaft_pass_ubo.bind(contract::BLOCK_SHAFT_PASS);
  p.set("u_sigma_t", static_cast<float>(sigma_t));
  p.set("u_sigma_s", static_cast<float>(scene.medium.scattering_per_m()));
  p.set("u_phase_kind", phase_code(scene.medium.phase.kind));
  p.set("u_phase_g", static_cast<float>(scene.medium.phase.g));
  glBindTextureUnit(contract::UNIT_SURFACE_RADIANCE, radiance.id());
  glBindTextureUnit(contract::UNIT_SCENE_DISTANCE, distance.id());
  glBindTextureUnit(contract::UNIT_JITTER, jitter_tex.id());
  method_pass.bind(*this, p);
  draw_fullscreen_triangle(empty_vao);
  check_gl("shaft pass");
}

namespace {

ShaftFrameStats frame_stats(GpuTimer& timer, ShaftFrameStats st) {
  timer.finish();
  st.shadow_maps_ms = timer.ms(kShadowMaps);
  st.surfaces_ms = timer.ms(kSurfaces);
  st.shadow_volume_ms = timer.ms(kShadowVolume);
  st.shafts_ms = timer.ms(kShafts);
  st.shadow_maps_fragments = timer.fragments(kShadowMaps);
  st.surfaces_fragments = timer.fragments(kSurfaces);
  st.shadow_volume_fragments = timer.fragments(kShadowVolume);
  st.shafts_fragments = timer.fragments(kShafts);
  st.total_ms = timer.total_ms();
  st.timing = timer.method();
  return st;
}

}  // namespace

Image ShaftRenderer::render(const Camera& camera, const ShaftMethod& method, ShaftFrameStats* stats) {
  validate(camera);
  Impl& s = *impl_;
  const std::unique_ptr<ShaftMethodPass> method_pass = make_shaft_method_pass(method, s.scene);
  ShaftFrameStats st;
  const int w = camera.width, h = camera.height;
  GpuTimer timer(kPassCount, stats != nullptr, GpuTimer::Clock::Wall);
  if (!s.shadow_maps_ready) timer.time(kShadowMaps, [&] { s.build_shadow_maps(); });

  s.ensure_targets(w, h);
  const CameraBlock camera_values = camera_block(camera);
  s.camera_block.update(camera_values);
  s.camera_block.bind(contract::BLOCK_CAMERA);
  timer.time(kSurfaces, [&] { s.draw_surfaces(camera_values, w, h); });
  method_pass->prepare(s, w, h, timer, st);
  s.ensure_jitter();
  const ShaderProgram& p = s.shaft_program(method);
  timer.time(kShafts, [&] { s.draw_shafts(camera, p, *method_pass); });

  Image img = read_rgba(s.out_fbo, w, h);
  st = frame_stats(timer, st);
  for (float& v : img.rgba)
    if (!std::isfinite(v)) throw std::runtime_error("GPU renderer produced a non-finite pixel value (method " + to_string(method) + ")");
  describe_frame(img, s.scene, camera, to_string(method));
  method_pass->describe(img);
  img.metadata["surface_airlight"] = s.settings.surface_airlight ? "on" : "off";
  img.metadata["shadow_map_res"] = std::to_string(s.settings.point_shadow_res) + " per cube face, sun " +
                                   std::to_string(s.settings.sun_shadow_res);
  if (stats) *stats = st;
  return img;
}

}  // namespace nimbus::render
