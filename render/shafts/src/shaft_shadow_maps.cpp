// The lights' shadow maps and shadow-volume skirts of the GPU shaft renderer: a distance cube map
// per point light, an orthographic distance map for the sun (shaders/shadow_distance.frag.glsl),
// and from them each light's skirts (shaders/shadow_volume_build.comp.glsl), all built once.
#include <algorithm>
#include <array>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "nimbus/render/scene/intersect.hpp"
#include "nimbus/render/core/shader_contract.hpp"
#include "nimbus/render/gl/to_float.hpp"
#include "nimbus/render/gl/uniform_blocks.hpp"
#include "shaft_renderer_impl.hpp"

namespace nimbus::render {
namespace {

using shaft_detail::draw;
using shaft_detail::kFarDistanceM;

// GL 4.5 table 8.19 face order +X, -X, +Y, -Y, +Z, -Z, with the "up" that makes a face rendered
// through a framebuffer match cube-map sampling.
const std::array<glm::dvec3, 6> kFaceDir = {glm::dvec3(1, 0, 0), glm::dvec3(-1, 0, 0), glm::dvec3(0, 1, 0),
                                            glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1)};
const std::array<glm::dvec3, 6> kFaceUp = {glm::dvec3(0, -1, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1),
                                           glm::dvec3(0, 0, -1), glm::dvec3(0, -1, 0), glm::dvec3(0, -1, 0)};

}  // namespace

void ShaftRenderer::Impl::build_shadow_maps() {
  n_point = static_cast<int>(scene.lamps.size());
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  shadow_program.use();
  if (n_point > 0) build_point_maps();
  if (scene.sun) build_sun_map();
  check_gl("rendering shadow maps");
  shadow_maps_ready = true;
}

// Each point light's distance to the nearest occluder, a cube map of six faces in one array.
void ShaftRenderer::Impl::build_point_maps() {
  const int res = settings.point_shadow_res;
  const float clear_far[4] = {kFarDistanceM, 0, 0, 0};
  const float clear_depth = 1.0f;
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
  UniformBuffer<ShadowMapBlock> block;
  block.bind(contract::BLOCK_SHADOW_MAP);
  for (int i = 0; i < n_point; ++i) {
    const glm::dvec3 pos = scene.lamps[static_cast<std::size_t>(i)].position_m;
    ShadowMapBlock lamp;
    lamp.mode = contract::SHADOW_POINT_LIGHT;
    lamp.origin = to_float(pos);
    block.update(lamp);
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

// The sun's orthographic distance map over the occluders' bounds, along its propagation direction.
void ShaftRenderer::Impl::build_sun_map() {
  const float clear_far[4] = {kFarDistanceM, 0, 0, 0};
  const float clear_depth = 1.0f;
  const int sres = settings.sun_shadow_res;
  sun_propagation = -glm::normalize(scene.sun->direction_to_sun);
  glm::dvec3 helper = std::abs(sun_propagation.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(helper, sun_propagation));
  const glm::dvec3 v = glm::cross(sun_propagation, u);
  // Bounds of the occluders along u, v and the propagation direction.
  glm::dvec3 lo(1e300), hi(-1e300);
  auto extend = [&](const glm::dvec3& p) {
    const glm::dvec3 c(glm::dot(p, u), glm::dot(p, v), glm::dot(p, sun_propagation));
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
  sun_origin = lo.x * u + lo.y * v + lo.z * sun_propagation;
  sun_axis_x = (hi.x - lo.x) * u;
  sun_axis_y = (hi.y - lo.y) * v;
  sun_texel_m = std::max(hi.x - lo.x, hi.y - lo.y) / sres;
  const double depth = hi.z - lo.z;
  // World -> clip: x, y from the map's axes, z from the distance along the propagation direction.
  glm::dmat4 m(0.0);
  const glm::dvec3 rx = 2.0 * u / (hi.x - lo.x), ry = 2.0 * v / (hi.y - lo.y), rz = 2.0 * sun_propagation / depth;
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
  ShadowMapBlock sun;
  sun.mode = contract::SHADOW_SUN;
  sun.origin = to_float(sun_origin);
  sun.to_sun = to_float(-sun_propagation);
  UniformBuffer<ShadowMapBlock> block;
  block.update(sun);
  block.bind(contract::BLOCK_SHADOW_MAP);
  shadow_program.set("u_view_proj", to_float(sun_view_proj));
  draw(occluders);
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
  UniformBuffer<ShadowMapBlock> block;
  block.bind(contract::BLOCK_SHADOW_MAP);
  if (point_maps) glBindTextureUnit(contract::UNIT_POINT_SHADOW, point_maps.id());
  if (sun_map) glBindTextureUnit(contract::UNIT_SUN_SHADOW, sun_map.id());
  skirts.clear();
  for (int layer = 0; layer < layers; ++layer) {
    const bool is_sun = layer >= n_point;
    const GLuint zero2[2] = {0, 0};
    glNamedBufferSubData(counter.id(), 0, sizeof(zero2), zero2);
    ShadowMapBlock m;
    m.rel_threshold = static_cast<float>(settings.silhouette_jump);
    m.max_distance = static_cast<float>(max_skirt_distance_m);
    m.max_quads = static_cast<unsigned>(max_quads);
    m.mode = is_sun ? contract::SHADOW_SUN : contract::SHADOW_POINT_LIGHT;
    m.layer = layer;
    if (is_sun) {
      m.res = settings.sun_shadow_res;
      m.origin = to_float(sun_origin);
      m.axis_x = to_float(sun_axis_x);
      m.axis_y = to_float(sun_axis_y);
      m.to_sun = to_float(-sun_propagation);
    } else {
      m.res = settings.point_shadow_res;
      m.origin = to_float(scene.lamps[static_cast<std::size_t>(layer)].position_m);
    }
    block.update(m);
    const int res = m.res;
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

}  // namespace nimbus::render
