// One light's pass of the half-angle slice renderer (cloud_light_pass.hpp): plan, uniforms, cloud
// blocks, the slice loop (shaders/cloud_slice.frag.glsl for the eye, cloud_light.frag.glsl for the
// light buffer, cloud_light_blur.frag.glsl for the forward-scattering cone) and, for a second
// light on, its radiance added into the eye buffer (cloud_accumulate.frag.glsl).
#include "cloud_light_pass.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "nimbus/render/core/shader_contract.hpp"
#include "nimbus/render/gl/to_float.hpp"

namespace nimbus::render::cloud_detail {
namespace {

// A jittered sample lies up to dt / 2 = d / (2 |dot(ray, s)|) along its ray from the plane, so a
// ray whose plane point misses the hull can still sample density inside it: the polygons are cut
// from the hulls grown by that much (the steepest ray at the image's corners).
double jitter_margin_m(const Camera& camera, const SliceAxis& axis, const SlicePlanes& planes) {
  double min_cos = 1.0;
  for (int c = 0; c < 4; ++c) {
    const glm::dvec3 r = pixel_ray(camera, (c & 1) ? camera.width - 1 : 0, (c & 2) ? camera.height - 1 : 0);
    min_cos = std::min(min_cos, std::abs(glm::dot(r, axis.axis)));
  }
  return std::min(0.5 / std::max(min_cos, 0.125), 4.0) * planes.spacing_m;
}

// The light buffer's frame: the sun's orthographic one, or the lamp's perspective one (and how
// many slice planes lie on the lamp's near side, where they see no shadow from the buffer).
void plan_light_frame(LightPassPlan& p, const std::vector<glm::dvec3>& hull_points, const Light& light,
                      const glm::dvec3& centre, int light_res, int pass) {
  if (!p.lamp) {
    p.light_frame = light_frame(hull_points, p.l, light_res);
    p.texel_m = p.light_frame.texel_m;
    return;
  }
  p.lamp_frame = lamp_frame(hull_points, light.position_m, p.l, light_res);
  const double r = glm::length(centre - light.position_m);  // a texel's width at the clouds' centre
  p.texel_m = std::max(r, 1e-9) * p.lamp_frame.texel_tan;
  const double lamp_s = glm::dot(p.axis.axis, light.position_m);
  int near_side = 0;
  for (int k = 0; k < p.planes.count; ++k) near_side += p.planes.first_m + k * p.planes.spacing_m <= lamp_s;
  std::ostringstream a;
  a << "lamp " << pass << ": " << near_side << " of " << p.planes.count << " slices on its near side"
    << (p.lamp_frame.clipped ? ", light buffer clipped" : "");
  p.note = a.str();
}

// The pass's light and slicing geometry as both slice programs read them (SliceLightBlock).
SliceLightBlock slice_light_block(const FrameContext& frame, const Light& light, const LightPassPlan& plan) {
  SliceLightBlock b;
  b.slice_axis = to_float(plan.axis.axis);
  b.spacing_m = static_cast<float>(plan.planes.spacing_m);
  b.light = light_record(light);
  if (plan.lamp) {
    b.world_to_lamp_clip = to_float(plan.lamp_frame.world_to_clip);
  } else {
    const LightFrame& lf = plan.light_frame;
    b.world_to_light_uv = to_float(lf.world_to_uv);
    b.light_slab_m = static_cast<float>(plan.light_slab_m);
    b.luv_eye = glm::vec2(lf.world_to_uv * glm::dvec4(frame.camera.eye, 1.0));
  }
  return b;
}

// This frame's jitter: the tile shifted along the R2 sequence, its values rotated by the golden
// ratio (Cranley-Patterson), so every pixel sees a new offset each frame.
void set_jitter_uniforms(const ShaderProgram& eye, const CloudSliceSettings& settings) {
  const double f = static_cast<double>(settings.frame);
  eye.set("u_jitter_offset", glm::ivec2(static_cast<int>(kJitterTile * (f * 0.7548776662466927 - std::floor(f * 0.7548776662466927))),
                                        static_cast<int>(kJitterTile * (f * 0.5698402909980532 - std::floor(f * 0.5698402909980532)))));
  eye.set("u_jitter_shift", static_cast<float>(f * 0.6180339887498949 - std::floor(f * 0.6180339887498949)));
  eye.set("u_jitter_on", settings.jitter ? 1.0f : 0.0f);
}

// Pass-constant uniforms of the eye and light programs beside the light's block: the view, the
// octaves, the light volume, the jitter and the fog.
void set_pass_uniforms(const CloudRenderer::Impl& s, const FrameContext& frame, const ShaderProgram& eye,
                       const ShaderProgram& lp, const LightPassPlan& plan) {
  const MultipleScattering& ms = frame.settings.multiple;
  eye.set("u_view_proj", frame.camera_block.view_proj);
  eye.set("u_octave_abc", glm::vec3(static_cast<float>(ms.occlusion), static_cast<float>(ms.contribution),
                                    static_cast<float>(ms.eccentricity)));
  if (frame.light_volume) s.bind_light_volume_grid();
  set_jitter_uniforms(eye, frame.settings);
  if (frame.underlay) {
    const Scene* scene = frame.underlay->scene;
    eye.set("u_fog_sigma_t", scene ? static_cast<float>(scene->medium.extinction_per_m) : 0.0f);
  }
  lp.set("u_view_proj", to_float(plan.lamp ? plan.lamp_frame.world_to_clip : plan.light_frame.world_to_clip));
}

// Kniss's cone: the light spreads by radius (slab along the light) tan(cone) per slice; a disk of
// radius R has variance R^2 / 4 per axis, which the 5-tap kernel reproduces. For a lamp, the
// texels and the slab are taken at the clouds' centre.
void set_blur_uniforms(const ShaderProgram& blur, const LightPassPlan& plan, double cone_rad) {
  glm::ivec2 step;
  glm::vec2 weight;
  for (int a = 0; a < 2; ++a) {
    const double r = plan.light_slab_m * std::tan(cone_rad) / plan.texel_m[a];  // texels
    step[a] = std::max(1, static_cast<int>(std::ceil(r / std::sqrt(2.0))));
    weight[a] = static_cast<float>(std::min(0.25, r * r / (8.0 * step[a] * step[a])));
  }
  blur.set("u_step", step);
  blur.set("u_weight", weight);
}

// Every copy's block for this pass (its cloud's optics, and what depends on the eye, the slabs and
// its offset); the ambient sky light enters once, with the first light.
std::vector<CloudBlock> cloud_blocks(const CloudRenderer::Impl& s, const PassClouds& pc, const FrameContext& frame,
                                     const LightPassPlan& plan, bool ambient) {
  std::vector<CloudBlock> blocks(pc.instances.size());
  for (std::size_t i = 0; i < pc.instances.size(); ++i) {
    const std::size_t j = pc.instances[i].cloud;
    const glm::dvec3 o = pc.instances[i].offset_m;
    const CloudVolume& c = s.clouds[j];
    CloudBlock& b = blocks[i];
    // The copy's texture map is its cloud's after moving back by the offset: world_to_texture * T(-o).
    glm::dmat4 world_to_texture = s.textures[j].world_to_texture;
    world_to_texture[3] = s.textures[j].world_to_texture * glm::dvec4(-o, 1.0);
    b.world_to_texture = to_float(world_to_texture);
    b.tc_eye = glm::vec3(world_to_texture * glm::dvec4(frame.camera.eye, 1.0));
    b.copy_offset_m = to_float(o);
    b.sigma_t = static_cast<float>(c.optics.extinction_per_m);
    b.albedo = to_float(c.optics.albedo);
    b.ambient = frame.settings.ambient && ambient ? to_float(c.optics.ambient_radiance) : glm::vec3(0.0f);
    b.phase = cloud_phase_lobes(c.optics.phase);
    b.tau_per_density = static_cast<float>(c.optics.extinction_per_m * plan.light_slab_m);
    b.blend = s.next_textures[j] ? static_cast<float>(c.blend) : 0.0f;
  }
  return blocks;
}

// Draws slice k's polygons, binding each copy's block and its cloud's textures when the copy changes.
class SliceDrawer {
 public:
  SliceDrawer(const CloudRenderer::Impl& s, const PassClouds& pc, const SliceMesh& mesh, bool copy_radiance)
      : s_(s), pc_(pc), mesh_(mesh), bound_(pc.instances.size()), copy_radiance_(copy_radiance) {}

  bool any(int k) const {
    const std::size_t n = pc_.instances.size();
    for (std::size_t j = 0; j < n; ++j)
      if (mesh_.count[static_cast<std::size_t>(k) * n + j] > 0) return true;
    return false;
  }

  void draw(int k) {
    const std::size_t n = pc_.instances.size();
    for (std::size_t j = 0; j < n; ++j) {
      const std::size_t idx = static_cast<std::size_t>(k) * n + j;
      if (mesh_.count[idx] == 0) continue;
      if (bound_ != j) bind(j);
      bound_ = j;
      glDrawArrays(GL_TRIANGLES, mesh_.first[idx], mesh_.count[idx]);
    }
  }

 private:
  void bind(std::size_t i) const {
    const std::size_t j = pc_.instances[i].cloud;
    s_.cloud_ubo.bind(contract::BLOCK_CLOUD, i);
    glBindTextureUnit(contract::UNIT_CLOUD_DENSITY, s_.textures[j].texture.id());
    const VolumeTexture& next = s_.next_textures[j] ? *s_.next_textures[j] : s_.textures[j];
    glBindTextureUnit(contract::UNIT_CLOUD_DENSITY_NEXT, next.texture.id());
    if (copy_radiance_) {
      const int k = pc_.radiance[i];
      glBindTextureUnit(contract::UNIT_LIGHT_RADIANCE, k < 0 ? s_.light_radiance_tex.id() : s_.copy_radiance_tex[k].id());
    }
  }

  const CloudRenderer::Impl& s_;
  const PassClouds& pc_;
  const SliceMesh& mesh_;
  std::size_t bound_;  // the copy whose block is bound (none yet: the count)
  bool copy_radiance_;  // each copy binds its own radiance toward the eye
};

// The slice loop: each slice is drawn into the eye target lit from the light buffer, then its
// optical depth is added into the light buffer (after the blur, when there is one) for the next.
int draw_slices(CloudRenderer::Impl& s, const PassClouds& pc, const FrameContext& frame, const LightPassPlan& plan,
                const ShaderProgram& eye, const ShaderProgram& lp, const GlFramebuffer& target, bool copy_radiance) {
  const bool blur = frame.settings.blur_cone_rad > 0.0;
  const int w = frame.camera.width, h = frame.camera.height;
  SliceDrawer slices(s, pc, plan.mesh, copy_radiance);
  int drawn = 0;
  int cur = 0;
  for (int k = 0; k < plan.planes.count; ++k) {
    const bool any = slices.any(k);
    if (any) {
      ++drawn;
      frame.timer.time(kEye, [&] {
        glBindFramebuffer(GL_FRAMEBUFFER, target.id());
        glViewport(0, 0, w, h);
        glEnable(GL_BLEND);
        if (plan.axis.front_to_back) {
          glBlendFunc(GL_ONE_MINUS_DST_ALPHA, GL_ONE);  // "under"
        } else {
          glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // "over"
        }
        glBindTextureUnit(contract::UNIT_LIGHT_BUFFER, s.light_tex[cur].id());
        eye.use();
        slices.draw(k);
      });
    }
    if (k + 1 == plan.planes.count) break;  // nothing reads the light buffer after the last slice
    if (!any && !blur) continue;
    frame.timer.time(kLight, [&] {
      glViewport(0, 0, s.light_res, s.light_res);
      if (blur) {  // next = blur(previous) + this slice
        const int next = 1 - cur;
        glBindFramebuffer(GL_FRAMEBUFFER, s.light_fbo[next].id());
        glDisable(GL_BLEND);
        glBindTextureUnit(contract::UNIT_LIGHT_BUFFER, s.light_tex[cur].id());
        s.blur_program.use();
        draw_fullscreen_triangle(s.empty_vao);
        glBindVertexArray(s.mesh_vao.id());
        cur = next;
      } else {
        glBindFramebuffer(GL_FRAMEBUFFER, s.light_fbo[cur].id());
      }
      glEnable(GL_BLEND);
      glBlendFunc(GL_ONE, GL_ONE);
      lp.use();
      slices.draw(k);
    });
  }
  return drawn;
}

// A later light's radiance into the eye buffer; its coverage is already there (the first pass's).
void accumulate_pass(CloudRenderer::Impl& s, const FrameContext& frame) {
  frame.timer.time(kEye, [&] {
    glBindFramebuffer(GL_FRAMEBUFFER, s.eye_fbo.id());
    glViewport(0, 0, frame.camera.width, frame.camera.height);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);
    glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glBindTextureUnit(contract::UNIT_CLOUD_COLOR, s.pass_color.id());
    s.accumulate_program->use();
    draw_fullscreen_triangle(s.empty_vao);
    glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glColorMaski(1, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  });
}

// The far copies' pass under everything in the eye buffer: eye += (1 - eye alpha) pass, for the
// radiance and, with an underlay, the distances the composite reads.
void under_pass(CloudRenderer::Impl& s, const FrameContext& frame) {
  frame.timer.time(kEye, [&] {
    glBindFramebuffer(GL_FRAMEBUFFER, s.eye_fbo.id());
    glViewport(0, 0, frame.camera.width, frame.camera.height);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE_MINUS_DST_ALPHA, GL_ONE);
    glBindTextureUnit(contract::UNIT_CLOUD_COLOR, s.pass_color.id());
    glBindTextureUnit(contract::UNIT_CLOUD_DISTANCE, s.pass_distance.id());
    s.under_program(frame.underlay != nullptr).use();
    draw_fullscreen_triangle(s.empty_vao);
  });
}

}  // namespace

PassClouds pass_clouds(const CloudRenderer::Impl& s, std::vector<CloudInstance> instances) {
  PassClouds pc;
  pc.instances = std::move(instances);
  for (const CloudInstance& i : pc.instances) {
    const glm::dvec3 o = i.offset_m;
    pc.moved = pc.moved || o != glm::dvec3(0.0);
    pc.hulls.push_back(o == glm::dvec3(0.0) ? s.hulls[i.cloud] : translated(s.hulls[i.cloud], o));
    for (const glm::dvec3& v : s.cloud_hull_points[i.cloud]) pc.hull_points.push_back(v + o);
  }
  return pc;
}

// The slices of a pass with copies (cloud_tiles.hpp): the near pass keeps the slab that the
// clouds alone (one copy each) get along the axis, up to three times the slices (a thicker slab
// shows as grain, through the jitter). The far pass, whose copies lie at least half a tile beyond
// the near ones and cover little of the frame, gets twice that slab, and never more than the
// settings' slices (docs/volume.md, "To the horizon": its cost against its error).
double extent_along(const std::vector<glm::dvec3>& points, const glm::dvec3& axis) {
  double lo = 1e300, hi = -1e300;
  for (const glm::dvec3& p : points) {
    lo = std::min(lo, glm::dot(p, axis));
    hi = std::max(hi, glm::dot(p, axis));
  }
  return hi > lo ? hi - lo : 0.0;
}

int tile_slices(const CloudRenderer::Impl& s, const PassClouds& pc, const glm::dvec3& axis, int slices) {
  if (!pc.moved && !pc.far) return slices;
  const double alone = extent_along(s.hull_points, axis);
  if (!(alone > 0.0)) return slices;
  const double ratio = extent_along(pc.hull_points, axis) / alone;
  const double scale = pc.far ? std::clamp(0.5 * ratio, 0.5, 1.0) : std::clamp(ratio, 1.0, 3.0);
  return std::min(4096, static_cast<int>(std::lround(slices * scale)));
}

LightPassPlan plan_light_pass(const CloudRenderer::Impl& s, const PassClouds& pc, const Camera& camera, const Light& light,
                              const glm::dvec3& centre, const CloudSliceSettings& settings, int pass) {
  LightPassPlan p;
  p.lamp = light.kind == LightKind::Point;
  // The axis, the planes and every polygon (Kniss et al. 2003). For a lamp, the axis takes the
  // light's direction at the clouds' centre (Kniss et al. for local lights).
  p.l = p.lamp ? (glm::length(centre - light.position_m) > 0.0 ? glm::normalize(centre - light.position_m)
                                                               : glm::dvec3(0.0, -1.0, 0.0))
               : -glm::normalize(light.direction_to_sun);
  p.axis = choose_slice_axis(camera_frame(camera).forward, p.l, settings.branch);
  p.planes = slice_planes(pc.hull_points, p.axis.axis, tile_slices(s, pc, p.axis.axis, settings.slices));
  const double margin_m = settings.jitter ? jitter_margin_m(camera, p.axis, p.planes) : 0.0;
  std::vector<ConvexHull> hulls;
  for (const ConvexHull& hull : pc.hulls) hulls.push_back(grown(hull, margin_m));
  p.mesh = build_slice_mesh(hulls, p.axis.axis, p.planes);
  // The slab between two planes is spacing / dot(l, s) thick along the light;
  // for a lamp, per fragment along each of its rays.
  p.light_slab_m = p.planes.spacing_m / std::max(glm::dot(p.l, p.axis.axis), 1e-3);
  plan_light_frame(p, pc.hull_points, light, centre, settings.light_res, pass);
  return p;
}

int draw_light_pass(CloudRenderer::Impl& s, const PassClouds& pc, const FrameContext& frame, const Light& light,
                    const LightPassPlan& plan, PassTarget to) {
  const CloudSliceSettings& settings = frame.settings;
  s.upload_mesh(plan.mesh);
  // The frame's radiance toward the eye was made at the clouds' own cells: copies read theirs,
  // made toward the eye moved back by their offsets, or the light volume per sample.
  const bool copy_radiance = pc.moved && pc.radiance.size() == pc.instances.size();
  const bool light_radiance = frame.light_radiance && (!pc.moved || copy_radiance);
  const ShaderProgram& eye = s.eye_program(frame.underlay != nullptr, frame.light_volume ? 0 : settings.multiple.octaves,
                                           frame.light_volume ? (light_radiance ? 2 : 1) : 0, plan.lamp);
  const ShaderProgram& lp = plan.lamp ? s.lamp_light_program : s.light_program;
  s.slice_light_ubo.update(slice_light_block(frame, light, plan));
  s.slice_light_ubo.bind(contract::BLOCK_SLICE_LIGHT);
  set_pass_uniforms(s, frame, eye, lp, plan);
  if (settings.blur_cone_rad > 0.0) set_blur_uniforms(s.blur_program, plan, settings.blur_cone_rad);
  s.cloud_ubo.update(cloud_blocks(s, pc, frame, plan, to != PassTarget::AddToEye));

  // The first pass draws into the eye buffer; the others into their own, added or put under after.
  const float zero[4] = {0, 0, 0, 0};
  const GlFramebuffer& target = to == PassTarget::Eye ? s.eye_fbo : s.pass_fbo;
  frame.timer.time(kLight, [&] { glClearNamedFramebufferfv(s.light_fbo[0].id(), GL_COLOR, 0, zero); });
  if (to != PassTarget::Eye)
    frame.timer.time(kEye, [&] {
      glClearNamedFramebufferfv(s.pass_fbo.id(), GL_COLOR, 0, zero);
      glClearNamedFramebufferfv(s.pass_fbo.id(), GL_COLOR, 1, zero);
    });
  glBindTextureUnit(contract::UNIT_JITTER, s.jitter.id());
  if (frame.light_volume) {
    glBindTextureUnit(contract::UNIT_LIGHT_VOLUME, s.light_volume_tex.id());
    if (light_radiance) glBindTextureUnit(contract::UNIT_LIGHT_RADIANCE, s.light_radiance_tex.id());
  }
  if (frame.underlay) glBindTextureUnit(contract::UNIT_SCENE_DISTANCE, frame.underlay->distance_texture);
  glBindVertexArray(s.mesh_vao.id());
  const int drawn = draw_slices(s, pc, frame, plan, eye, lp, target, light_radiance && copy_radiance);
  if (to == PassTarget::AddToEye) accumulate_pass(s, frame);
  if (to == PassTarget::UnderEye) under_pass(s, frame);
  glDisable(GL_BLEND);
  check_gl("cloud slices");
  return drawn;
}

}  // namespace nimbus::render::cloud_detail
