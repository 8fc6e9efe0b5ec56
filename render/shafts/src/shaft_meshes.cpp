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
    // Under a sky the ground reaches the sky's distance from wherever the camera stands.
    const double extent = scene.sky ? std::max(settings.ground_extent_m, 3.0 * scene.sky->distance_m)
                                    : settings.ground_extent_m;
    ground = upload(build_scene_mesh(g, extent));
  }
  for (const Light& l : scene.lamps) {
    bulbs.push_back(upload(build_bulb_mesh(l)));
  }
  empty_vao = make_vertex_array();
}

}  // namespace nimbus::render
