// The scene's meshes on the GPU for the shaft renderer (shaders/lib/scene_vertex.glsl): the
// occluders, the ground (reaching the sky's distance under a sky) and each point light's bulb.
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "shaft_renderer_impl.hpp"

namespace nimbus::render {
namespace shaft_detail {

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

}  // namespace shaft_detail

using namespace shaft_detail;

void ShaftRenderer::Impl::build_meshes() {
  Scene occ = scene;
  occ.ground.reset();
  occluders = upload(build_scene_mesh(occ, settings.ground_extent_m));
  if (scene.ground) {
    Scene g;
    g.ground = scene.ground;
    // Under a sky the ground reaches the horizon: kHorizonGroundM from wherever the camera
    // stands, so an eye 400 m up sees its edge 0.011 degrees below the horizon (a quarter of a
    // pixel of a 1280-wide frame at 60 degrees). The surface pass draws it unclipped by the far
    // plane, at its exact point on each pixel's ray.
    const double extent = scene.sky ? std::max(settings.ground_extent_m, kHorizonGroundM) : settings.ground_extent_m;
    ground = upload(build_scene_mesh(g, extent));
    if (const auto& tex = scene.ground->albedo_texture) {
      const int n = tex->params.size;
      ground_albedo = make_texture_2d(GL_RGB32F, n, n, TextureParams{GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_REPEAT, tex->level_count()});
      for (int l = 0; l < tex->level_count(); ++l)
        glTextureSubImage2D(ground_albedo.id(), l, 0, 0, tex->size(l), tex->size(l), GL_RGB, GL_FLOAT, tex->levels[l].data());
      check_gl("uploading the ground's albedo texture");
    }
  }
  for (const Light& l : scene.lamps) {
    bulbs.push_back(upload(build_bulb_mesh(l)));
  }
  empty_vao = make_vertex_array();
}

}  // namespace nimbus::render
