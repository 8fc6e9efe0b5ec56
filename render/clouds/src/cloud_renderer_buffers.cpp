// The half-angle slice renderer's GPU resources (cloud_renderer_impl.hpp): its programs by
// variant, the slice polygons' buffer, and the light, eye and pass buffers, each made again only
// when its size changes.
#include <algorithm>
#include <string>
#include <vector>

#include "cloud_renderer_impl.hpp"

namespace nimbus::render {

const ShaderProgram& CloudRenderer::Impl::eye_program(bool underlay, int octaves, int ms_volume, bool lamp) {
  const auto key = std::make_tuple(underlay, octaves, ms_volume, lamp);
  auto it = eye_programs.find(key);
  if (it == eye_programs.end()) {
    const std::string defines = "#define UNDERLAY " + std::string(underlay ? "1" : "0") + "\n#define OCTAVES " +
                                std::to_string(octaves) + "\n#define MS_VOLUME " + std::to_string(ms_volume) +
                                "\n#define LAMP " + (lamp ? "1" : "0") + "\n";
    it = eye_programs.emplace(key, ShaderProgram({"cloud_slice.vert.glsl", "cloud_slice.frag.glsl"}, defines)).first;
  }
  return it->second;
}

const ShaderProgram& CloudRenderer::Impl::under_program(bool underlay) {
  std::optional<ShaderProgram>& p = under_programs[underlay ? 1 : 0];
  if (!p)
    p.emplace(std::vector<std::string>{"fullscreen.vert.glsl", "cloud_under.frag.glsl"},
              std::string("#define UNDERLAY ") + (underlay ? "1" : "0") + "\n");
  return *p;
}

void CloudRenderer::Impl::upload_mesh(const cloud_detail::SliceMesh& mesh) {
  if (mesh.vertices.size() > mesh_capacity) {
    mesh_capacity = std::max<std::size_t>(mesh.vertices.size(), 2 * mesh_capacity);
    mesh_buffer = make_buffer(static_cast<GLsizeiptr>(mesh_capacity * sizeof(glm::vec3)));
    mesh_vao = make_vertex_array();
    const GLuint vao = mesh_vao.id();
    glVertexArrayVertexBuffer(vao, 0, mesh_buffer.id(), 0, sizeof(glm::vec3));
    glEnableVertexArrayAttrib(vao, 0);
    glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, 0, 0);
  }
  if (!mesh.vertices.empty())
    glNamedBufferSubData(mesh_buffer.id(), 0, static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(glm::vec3)),
                         mesh.vertices.data());
  check_gl("uploading slice polygons");
}

void CloudRenderer::Impl::ensure_light_buffers(int res) {
  if (res == light_res) return;
  for (int i = 0; i < 2; ++i) {
    // Linear filtering; border 0 outside the footprint (no cloud there).
    light_tex[i] = make_texture_2d(GL_R32F, res, res, TextureParams{GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_BORDER, 1});
    light_fbo[i] = make_framebuffer({{GL_COLOR_ATTACHMENT0, light_tex[i].id()}});
  }
  light_res = res;
}

void CloudRenderer::Impl::ensure_eye_buffers(int w, int h, bool distance) {
  if (w == eye_w && h == eye_h && distance == eye_has_distance) return;
  const TextureParams nearest{GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE, 1};
  eye_color = make_texture_2d(GL_RGBA32F, w, h, nearest);
  if (distance) {
    eye_distance = make_texture_2d(GL_RGBA32F, w, h, nearest);
    eye_fbo = make_framebuffer({{GL_COLOR_ATTACHMENT0, eye_color.id()}, {GL_COLOR_ATTACHMENT1, eye_distance.id()}});
    out_color = make_texture_2d(GL_RGBA32F, w, h, nearest);
    out_depth = make_texture_2d(GL_RG32F, w, h, nearest);
    out_fbo = make_framebuffer({{GL_COLOR_ATTACHMENT0, out_color.id()}, {GL_COLOR_ATTACHMENT1, out_depth.id()}});
  } else {
    eye_distance.reset();
    out_color.reset();
    out_depth.reset();
    out_fbo.reset();
    eye_fbo = make_framebuffer({{GL_COLOR_ATTACHMENT0, eye_color.id()}});
  }
  eye_w = w;
  eye_h = h;
  eye_has_distance = distance;
}

void CloudRenderer::Impl::ensure_pass_buffers(int w, int h) {
  if (w == pass_w && h == pass_h) return;
  const TextureParams nearest{GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE, 1};
  pass_color = make_texture_2d(GL_RGBA32F, w, h, nearest);
  pass_distance = make_texture_2d(GL_RGBA32F, w, h, nearest);  // written by the underlay variant, not read
  pass_fbo = make_framebuffer({{GL_COLOR_ATTACHMENT0, pass_color.id()}, {GL_COLOR_ATTACHMENT1, pass_distance.id()}});
  pass_w = w;
  pass_h = h;
}

void CloudRenderer::Impl::prepare_frame(int w, int h, const CloudSliceSettings& settings, std::size_t passes,
                                        bool underlay) {
  ensure_light_buffers(settings.light_res);
  ensure_eye_buffers(w, h, underlay);
  if (passes > 1) {
    ensure_pass_buffers(w, h);
    if (!accumulate_program)
      accumulate_program.emplace(std::vector<std::string>{"fullscreen.vert.glsl", "cloud_accumulate.frag.glsl"});
  }
}

}  // namespace nimbus::render
