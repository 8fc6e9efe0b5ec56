// A headless OpenGL 4.5 core context through EGL: a GPU's EGL device when there is one, else
// Mesa's software renderer (llvmpipe) on the surfaceless platform. See docs/gl.md.
#pragma once
#include <memory>
#include <stdexcept>
#include <string>

namespace nimbus::render {

// No OpenGL 4.5 core context can be had; what() is one line naming the reason.
struct GlUnavailable : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Owns an EGL display reference and a context with no default framebuffer (draw into
// framebuffer objects). The renderer never creates one: it draws into whatever is current.
class GlContext {
 public:
  // Chooses the EGL device (env NIMBUS_EGL_DEVICE=<index>|software forces one), creates a 4.5
  // core context and makes it current on the calling thread. Throws GlUnavailable.
  static std::unique_ptr<GlContext> create_headless();

  const std::string& renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  const std::string& version() const;   // GL_VERSION, e.g. "4.5 (Core Profile) Mesa 22.3.6"
  const std::string& platform() const;  // how it was made, e.g. "EGL device 0" or "EGL surfaceless (Mesa)"
  bool is_software() const;             // a CPU rasteriser (llvmpipe, softpipe, ...)
  void make_current();                  // on the calling thread

  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  struct Impl;

 private:
  explicit GlContext(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace nimbus::render
