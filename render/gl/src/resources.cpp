// Creation and deletion of GL objects (direct state access), framebuffer completeness, errors.
#include "nimbus/render/gl/resources.hpp"

#include <algorithm>
#include <cstdio>
#include <vector>

namespace nimbus::render {

std::string gl_enum_name(GLenum value) {
  switch (value) {
    case GL_NO_ERROR: return "GL_NO_ERROR";
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_CONTEXT_LOST: return "GL_CONTEXT_LOST";
    case GL_FRAMEBUFFER_COMPLETE: return "GL_FRAMEBUFFER_COMPLETE";
    case GL_FRAMEBUFFER_UNDEFINED: return "GL_FRAMEBUFFER_UNDEFINED";
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT: return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT: return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER: return "GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER";
    case GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER: return "GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER";
    case GL_FRAMEBUFFER_UNSUPPORTED: return "GL_FRAMEBUFFER_UNSUPPORTED";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE: return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
    case GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS: return "GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS";
    default: {
      char buf[16];
      std::snprintf(buf, sizeof buf, "0x%04X", value);
      return buf;
    }
  }
}

void check_gl(const char* where) {
  std::string errors;
  bool oom = false;
  // glGetError returns one flag per call; a lost context repeats GL_CONTEXT_LOST, hence the bound.
  for (int i = 0; i < 16; ++i) {
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR) break;
    oom |= e == GL_OUT_OF_MEMORY;
    errors += (errors.empty() ? "" : ", ") + gl_enum_name(e);
  }
  if (!errors.empty()) throw GlError("GL error " + errors + " at " + where, oom);
}

void delete_gl_object(GlKind kind, GLuint id) {
  switch (kind) {
    case GlKind::Texture: glDeleteTextures(1, &id); break;
    case GlKind::Framebuffer: glDeleteFramebuffers(1, &id); break;
    case GlKind::Buffer: glDeleteBuffers(1, &id); break;
    case GlKind::VertexArray: glDeleteVertexArrays(1, &id); break;
    case GlKind::Query: glDeleteQueries(1, &id); break;
    case GlKind::Renderbuffer: glDeleteRenderbuffers(1, &id); break;
  }
}

namespace {

void require_positive(int value, const char* field) {
  if (value < 1) throw std::invalid_argument(std::string(field) + " must be >= 1 (got " + std::to_string(value) + ")");
}

void require_levels(int levels, int largest) {
  int full = 1;
  while ((largest >> full) > 0) ++full;
  if (levels < 1 || levels > full) {
    throw std::invalid_argument("levels must be in [1, " + std::to_string(full) + "] (got " +
                                std::to_string(levels) + ")");
  }
}

void apply_params(GLuint tex, const TextureParams& p, bool three_d) {
  glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(p.min_filter));
  glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(p.mag_filter));
  glTextureParameteri(tex, GL_TEXTURE_WRAP_S, static_cast<GLint>(p.wrap));
  glTextureParameteri(tex, GL_TEXTURE_WRAP_T, static_cast<GLint>(p.wrap));
  if (three_d) glTextureParameteri(tex, GL_TEXTURE_WRAP_R, static_cast<GLint>(p.wrap));
  glTextureParameteri(tex, GL_TEXTURE_MAX_LEVEL, p.levels - 1);
}

void apply_depth_params(GLuint tex, const DepthParams& p, bool cube) {
  glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(p.filter));
  glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(p.filter));
  glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  if (cube) glTextureParameteri(tex, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
  glTextureParameteri(tex, GL_TEXTURE_MAX_LEVEL, 0);
  if (p.compare) {
    glTextureParameteri(tex, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(tex, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  }
}

}  // namespace

GlTexture make_texture_2d(GLenum internal_format, int width, int height, const TextureParams& params) {
  require_positive(width, "width");
  require_positive(height, "height");
  require_levels(params.levels, std::max(width, height));
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &id);
  GlTexture tex(id);
  glTextureStorage2D(id, params.levels, internal_format, width, height);
  apply_params(id, params, false);
  check_gl("make_texture_2d");
  return tex;
}

GlTexture make_texture_3d(GLenum internal_format, int width, int height, int depth, const TextureParams& params) {
  require_positive(width, "width");
  require_positive(height, "height");
  require_positive(depth, "depth");
  require_levels(params.levels, std::max({width, height, depth}));
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_3D, 1, &id);
  GlTexture tex(id);
  glTextureStorage3D(id, params.levels, internal_format, width, height, depth);
  apply_params(id, params, true);
  check_gl("make_texture_3d");
  return tex;
}

GlTexture make_depth_texture(int width, int height, const DepthParams& params) {
  require_positive(width, "width");
  require_positive(height, "height");
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &id);
  GlTexture tex(id);
  glTextureStorage2D(id, 1, params.internal_format, width, height);
  apply_depth_params(id, params, false);
  check_gl("make_depth_texture");
  return tex;
}

GlTexture make_depth_cube_texture(int size, const DepthParams& params) {
  require_positive(size, "size");
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &id);
  GlTexture tex(id);
  glTextureStorage2D(id, 1, params.internal_format, size, size);
  apply_depth_params(id, params, true);
  check_gl("make_depth_cube_texture");
  return tex;
}

GlBuffer make_buffer(GLsizeiptr bytes, const void* data, GLbitfield flags) {
  if (bytes < 1) throw std::invalid_argument("bytes must be >= 1 (got " + std::to_string(bytes) + ")");
  GLuint id = 0;
  glCreateBuffers(1, &id);
  GlBuffer buf(id);
  glNamedBufferStorage(id, bytes, data, flags);
  check_gl("make_buffer");
  return buf;
}

GlVertexArray make_vertex_array() {
  GLuint id = 0;
  glCreateVertexArrays(1, &id);
  return GlVertexArray(id);
}

GlQuery make_query(GLenum target) {
  GLuint id = 0;
  glCreateQueries(target, 1, &id);
  check_gl("make_query");
  return GlQuery(id);
}

GlFramebuffer make_framebuffer(std::initializer_list<FramebufferAttachment> attachments) {
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  GlFramebuffer fb(id);
  std::vector<GLenum> draw_buffers;
  for (const auto& a : attachments) {
    if (a.layer < 0) {
      glNamedFramebufferTexture(id, a.attachment, a.texture, a.level);
    } else {
      glNamedFramebufferTextureLayer(id, a.attachment, a.texture, a.level, a.layer);
    }
    if (a.attachment >= GL_COLOR_ATTACHMENT0 && a.attachment <= GL_COLOR_ATTACHMENT31) {
      draw_buffers.push_back(a.attachment);
    }
  }
  if (draw_buffers.empty()) {
    glNamedFramebufferDrawBuffer(id, GL_NONE);
    glNamedFramebufferReadBuffer(id, GL_NONE);
  } else {
    glNamedFramebufferDrawBuffers(id, static_cast<GLsizei>(draw_buffers.size()), draw_buffers.data());
    glNamedFramebufferReadBuffer(id, draw_buffers.front());
  }
  check_gl("make_framebuffer (attaching)");
  const GLenum status = glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) throw GlError("framebuffer incomplete: " + gl_enum_name(status));
  return fb;
}

void draw_fullscreen_triangle(const GlVertexArray& vao) {
  glBindVertexArray(vao.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace nimbus::render
