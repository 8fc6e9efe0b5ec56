// Move-only RAII owners of OpenGL objects, the texture/framebuffer makers the renderer uses, and
// check_gl. All need a current GL 4.5 context (direct state access, glCreate*).
#pragma once
#include <epoxy/gl.h>

#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>

namespace nimbus::render {

// glGetError reported an error, or a framebuffer is incomplete; what() names where and which.
// out_of_memory: GL_OUT_OF_MEMORY was among the errors (buffers too large for the device), which
// a caller can name as the size it asked for.
struct GlError : std::runtime_error {
  explicit GlError(const std::string& what, bool oom = false) : std::runtime_error(what), out_of_memory(oom) {}
  bool out_of_memory = false;
};

// "GL_INVALID_OPERATION", "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT", ... or "0x1234".
std::string gl_enum_name(GLenum value);

// Throws GlError("GL error GL_INVALID_VALUE (and ...) at <where>") when glGetError has any.
void check_gl(const char* where);

enum class GlKind { Texture, Framebuffer, Buffer, VertexArray, Query, Renderbuffer };
void delete_gl_object(GlKind kind, GLuint id);

// Owns one GL object name of kind K (0 = none).
template <GlKind K>
class GlObject {
 public:
  GlObject() = default;
  explicit GlObject(GLuint id) : id_(id) {}
  GlObject(GlObject&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  GlObject& operator=(GlObject&& other) noexcept {
    if (this != &other) reset(std::exchange(other.id_, 0));
    return *this;
  }
  GlObject(const GlObject&) = delete;
  GlObject& operator=(const GlObject&) = delete;
  ~GlObject() { reset(); }

  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  GLuint release() { return std::exchange(id_, 0); }
  void reset(GLuint id = 0) {
    if (id_ != 0) delete_gl_object(K, id_);
    id_ = id;
  }

 private:
  GLuint id_ = 0;
};

using GlTexture = GlObject<GlKind::Texture>;
using GlFramebuffer = GlObject<GlKind::Framebuffer>;
using GlBuffer = GlObject<GlKind::Buffer>;
using GlVertexArray = GlObject<GlKind::VertexArray>;
using GlQuery = GlObject<GlKind::Query>;
using GlRenderbuffer = GlObject<GlKind::Renderbuffer>;

struct TextureParams {
  GLenum min_filter = GL_LINEAR;  // GL_NEAREST, GL_LINEAR, GL_LINEAR_MIPMAP_LINEAR (needs levels > 1)
  GLenum mag_filter = GL_LINEAR;
  GLenum wrap = GL_CLAMP_TO_EDGE;  // every axis
  int levels = 1;                  // mipmap levels allocated
};

// Immutable storage (glTextureStorage*), contents undefined. Sizes in texels; a size < 1 or a
// level count beyond the full chain -> std::invalid_argument naming the field.
GlTexture make_texture_2d(GLenum internal_format, int width, int height, const TextureParams& params = {});
GlTexture make_texture_3d(GLenum internal_format, int width, int height, int depth,
                          const TextureParams& params = {});

struct DepthParams {
  GLenum internal_format = GL_DEPTH_COMPONENT32F;
  // GL_COMPARE_REF_TO_TEXTURE with GL_LEQUAL, for sampler2DShadow / samplerCubeShadow.
  bool compare = false;
  GLenum filter = GL_NEAREST;  // GL_LINEAR with compare gives 2x2 percentage-closer filtering
};
GlTexture make_depth_texture(int width, int height, const DepthParams& params = {});
// A cube map of six size x size depth faces (point-light shadows); faces are layers 0..5 in
// the order +X, -X, +Y, -Y, +Z, -Z.
GlTexture make_depth_cube_texture(int size, const DepthParams& params = {});

// glCreateBuffers + glNamedBufferStorage(bytes, data (may be null), flags).
GlBuffer make_buffer(GLsizeiptr bytes, const void* data = nullptr, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
GlVertexArray make_vertex_array();  // an empty one is what a full-screen triangle draws with
GlQuery make_query(GLenum target);  // e.g. GL_TIME_ELAPSED

struct FramebufferAttachment {
  GLenum attachment;  // GL_COLOR_ATTACHMENTi, GL_DEPTH_ATTACHMENT, ...
  GLuint texture;
  GLint level = 0;
  GLint layer = -1;  // -1: the whole texture (layered for cube maps/3D); else one layer / cube face
};

// A framebuffer with these attachments; its draw buffers are the color attachments in the
// given order (GL_NONE when there are none). Incomplete -> GlError naming the status, e.g.
// "framebuffer incomplete: GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT".
GlFramebuffer make_framebuffer(std::initializer_list<FramebufferAttachment> attachments);

// Binds `vao` (an empty vertex array) and draws the 3 vertices of shaders/fullscreen.vert.glsl.
void draw_fullscreen_triangle(const GlVertexArray& vao);

}  // namespace nimbus::render
