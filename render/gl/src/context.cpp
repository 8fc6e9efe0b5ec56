// Headless OpenGL 4.5 core contexts through EGL: hardware EGL devices first, then Mesa's
// surfaceless platform (llvmpipe), then any software EGL device; NIMBUS_EGL_DEVICE forces one.
#include "nimbus/render/gl/context.hpp"

// epoxy's EGL header, not <EGL/egl.h>: the Khronos headers clash with epoxy's GL types.
#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace nimbus::render {
namespace {

constexpr const char* kUnavailable = "no OpenGL 4.5 core context available: ";

std::string egl_error_name(EGLint e) {
  switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    default: {
      char buf[32];
      std::snprintf(buf, sizeof buf, "EGL error 0x%04x", static_cast<unsigned>(e));
      return buf;
    }
  }
}

std::string last_egl_error() { return egl_error_name(eglGetError()); }

bool has_extension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n) {
    const bool starts = p == list || p[-1] == ' ';
    const bool ends = p[n] == '\0' || p[n] == ' ';
    if (starts && ends) return true;
  }
  return false;
}

// eglInitialize/eglTerminate are not reference-counted by EGL itself: two contexts on one
// display must not terminate it under each other.
std::mutex g_display_mutex;
std::map<EGLDisplay, int> g_display_refs;

bool acquire_display(EGLDisplay d, std::string& why) {
  std::lock_guard lock(g_display_mutex);
  int& refs = g_display_refs[d];
  if (refs == 0) {
    EGLint major = 0, minor = 0;
    if (eglInitialize(d, &major, &minor) != EGL_TRUE) {
      why = "eglInitialize failed (" + last_egl_error() + ")";
      g_display_refs.erase(d);
      return false;
    }
  }
  ++refs;
  return true;
}

void release_display(EGLDisplay d) {
  std::lock_guard lock(g_display_mutex);
  auto it = g_display_refs.find(d);
  if (it == g_display_refs.end()) return;
  if (--it->second == 0) {
    eglTerminate(d);
    g_display_refs.erase(it);
  }
}

struct EglFunctions {
  PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display = nullptr;
  PFNEGLQUERYDEVICESEXTPROC query_devices = nullptr;
  PFNEGLQUERYDEVICESTRINGEXTPROC query_device_string = nullptr;
};

EglFunctions load_egl_functions() {
  EglFunctions f;
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (has_extension(client, "EGL_EXT_platform_base")) {
    f.get_platform_display =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  }
  if (has_extension(client, "EGL_EXT_device_enumeration") || has_extension(client, "EGL_EXT_device_base")) {
    f.query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    f.query_device_string =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
  }
  return f;
}

struct Device {
  EGLDeviceEXT handle;
  bool software;
};

std::vector<Device> list_devices(const EglFunctions& f) {
  std::vector<Device> out;
  if (f.query_devices == nullptr) return out;
  EGLint count = 0;
  if (f.query_devices(0, nullptr, &count) != EGL_TRUE || count <= 0) return out;
  std::vector<EGLDeviceEXT> handles(static_cast<std::size_t>(count));
  if (f.query_devices(count, handles.data(), &count) != EGL_TRUE) return out;
  handles.resize(static_cast<std::size_t>(count));
  for (EGLDeviceEXT h : handles) {
    const char* ext = f.query_device_string ? f.query_device_string(h, EGL_EXTENSIONS) : nullptr;
    out.push_back({h, has_extension(ext, "EGL_MESA_device_software")});
  }
  return out;
}

// True when the renderer string names a CPU rasteriser.
bool renderer_is_software(const std::string& r) {
  for (const char* s : {"llvmpipe", "softpipe", "swrast", "SwiftShader", "Software Rasterizer"}) {
    if (r.find(s) != std::string::npos) return true;
  }
  return false;
}

}  // namespace

struct GlContext::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  std::string renderer, version, platform;
  bool software = false;

  ~Impl() {
    if (display == EGL_NO_DISPLAY) return;
    if (context != EGL_NO_CONTEXT) {
      if (eglGetCurrentContext() == context) eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroyContext(display, context);
    }
    release_display(display);
  }
};

namespace {

// Makes a 4.5 core context on `display` current (no surface); nullptr and `why` on failure.
std::unique_ptr<GlContext::Impl> try_display(EGLDisplay display, const std::string& platform,
                                             bool device_is_software, std::string& why) {
  if (display == EGL_NO_DISPLAY) {
    why = platform + ": no display (" + last_egl_error() + ")";
    return nullptr;
  }
  if (!acquire_display(display, why)) {
    why = platform + ": " + why;
    return nullptr;
  }
  auto impl = std::make_unique<GlContext::Impl>();
  impl->display = display;
  impl->platform = platform;
  const char* ext = eglQueryString(display, EGL_EXTENSIONS);
  if (!has_extension(ext, "EGL_KHR_surfaceless_context")) {
    why = platform + ": no EGL_KHR_surfaceless_context";
    return nullptr;
  }
  if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
    why = platform + ": eglBindAPI(EGL_OPENGL_API) failed (" + last_egl_error() + ")";
    return nullptr;
  }
  // Surface type 0: any config (we never make a surface; FBOs only).
  const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint n = 0;
  if (eglChooseConfig(display, config_attribs, &config, 1, &n) != EGL_TRUE || n < 1) {
    why = platform + ": no EGL config renders OpenGL (" + last_egl_error() + ")";
    return nullptr;
  }
  const char* debug_env = std::getenv("NIMBUS_GL_DEBUG");
  const bool debug = debug_env != nullptr && *debug_env != '\0' && std::strcmp(debug_env, "0") != 0;
  const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4,
                                    EGL_CONTEXT_MINOR_VERSION, 5,
                                    EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                    EGL_CONTEXT_OPENGL_DEBUG, debug ? EGL_TRUE : EGL_FALSE,
                                    EGL_NONE};
  impl->context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attribs);
  if (impl->context == EGL_NO_CONTEXT) {
    why = platform + ": eglCreateContext(4.5 core) failed (" + last_egl_error() + ")";
    return nullptr;
  }
  if (eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl->context) != EGL_TRUE) {
    why = platform + ": eglMakeCurrent failed (" + last_egl_error() + ")";
    return nullptr;
  }
  GLint major = 0, minor = 0, profile = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  const auto str = [](GLenum e) {
    const auto* s = reinterpret_cast<const char*>(glGetString(e));
    return std::string(s ? s : "");
  };
  impl->renderer = str(GL_RENDERER);
  impl->version = str(GL_VERSION);
  if (major * 10 + minor < 45 || (profile & GL_CONTEXT_CORE_PROFILE_BIT) == 0) {
    why = platform + ": got OpenGL " + impl->version + " on " + impl->renderer + ", not 4.5 core";
    return nullptr;
  }
  impl->software = device_is_software || renderer_is_software(impl->renderer);
  if (debug) {
    glDebugMessageCallback(
        [](GLenum, GLenum type, GLuint, GLenum severity, GLsizei, const GLchar* message, const void*) {
          if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
          std::fprintf(stderr, "GL debug%s: %s\n", type == GL_DEBUG_TYPE_ERROR ? " error" : "", message);
        },
        nullptr);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  }
  return impl;
}

std::unique_ptr<GlContext::Impl> try_device(const EglFunctions& f, const std::vector<Device>& devices,
                                            std::size_t index, std::string& why) {
  const std::string name = "EGL device " + std::to_string(index) + (devices[index].software ? " (software)" : "");
  if (f.get_platform_display == nullptr) {
    why = name + ": no eglGetPlatformDisplayEXT";
    return nullptr;
  }
  EGLDisplay d = f.get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[index].handle, nullptr);
  return try_display(d, name, devices[index].software, why);
}

std::unique_ptr<GlContext::Impl> try_surfaceless(const EglFunctions& f, std::string& why) {
  const std::string name = "EGL surfaceless platform (Mesa)";
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (f.get_platform_display == nullptr || !has_extension(client, "EGL_MESA_platform_surfaceless")) {
    why = name + ": not offered by any EGL vendor (no EGL_MESA_platform_surfaceless)";
    return nullptr;
  }
  EGLDisplay d = f.get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  return try_display(d, name, false, why);
}

std::string join(const std::vector<std::string>& parts) {
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : "; ") + p;
  return out;
}

}  // namespace

GlContext::GlContext(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
GlContext::~GlContext() = default;

const std::string& GlContext::renderer() const { return impl_->renderer; }
const std::string& GlContext::version() const { return impl_->version; }
const std::string& GlContext::platform() const { return impl_->platform; }
bool GlContext::is_software() const { return impl_->software; }

void GlContext::make_current() {
  if (eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl_->context) != EGL_TRUE) {
    throw GlUnavailable("eglMakeCurrent failed (" + last_egl_error() + ") on " + impl_->platform);
  }
}

std::unique_ptr<GlContext> GlContext::create_headless() {
  // NIMBUS_EGL_DEVICE: "" (choose), "software", or a device index; a bad value is named first.
  const char* forced = std::getenv("NIMBUS_EGL_DEVICE");
  const std::string forced_value = forced != nullptr ? forced : "";
  long forced_index = -1;
  if (!forced_value.empty() && forced_value != "software") {
    char* end = nullptr;
    forced_index = std::strtol(forced_value.c_str(), &end, 10);
    if (end == forced_value.c_str() || *end != '\0' || forced_index < 0) {
      throw GlUnavailable(kUnavailable + ("NIMBUS_EGL_DEVICE='" + forced_value +
                                          "' is neither a device index nor 'software'"));
    }
  }
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (client == nullptr || *client == '\0') {
    // glvnd answers with an empty list when it loaded no vendor library at all.
    throw GlUnavailable(kUnavailable + std::string("no EGL vendor library could be loaded (libglvnd found none; "
                                                   "install libegl-mesa0 or a GPU driver's EGL, and check "
                                                   "__EGL_VENDOR_LIBRARY_FILENAMES)"));
  }
  const EglFunctions f = load_egl_functions();
  const std::vector<Device> devices = list_devices(f);
  std::vector<std::string> failures;
  std::string why;
  const auto done = [](std::unique_ptr<Impl> impl) {
    return std::unique_ptr<GlContext>(new GlContext(std::move(impl)));
  };

  if (!forced_value.empty()) {
    const std::string& value = forced_value;
    if (value == "software") {
      if (auto impl = try_surfaceless(f, why)) return done(std::move(impl));
      failures.push_back(why);
      for (std::size_t i = 0; i < devices.size(); ++i) {
        if (!devices[i].software) continue;
        if (auto impl = try_device(f, devices, i, why)) return done(std::move(impl));
        failures.push_back(why);
      }
      throw GlUnavailable(kUnavailable + ("NIMBUS_EGL_DEVICE=software: " + join(failures)));
    }
    const long index = forced_index;
    if (static_cast<std::size_t>(index) >= devices.size()) {
      throw GlUnavailable(kUnavailable + ("NIMBUS_EGL_DEVICE=" + value + " is out of range: " +
                                          std::to_string(devices.size()) + " EGL device(s), numbered from 0"));
    }
    if (auto impl = try_device(f, devices, static_cast<std::size_t>(index), why)) return done(std::move(impl));
    throw GlUnavailable(kUnavailable + ("NIMBUS_EGL_DEVICE=" + value + ": " + why));
  }

  for (std::size_t i = 0; i < devices.size(); ++i) {
    if (devices[i].software) continue;
    if (auto impl = try_device(f, devices, i, why)) return done(std::move(impl));
    failures.push_back(why);
  }
  if (auto impl = try_surfaceless(f, why)) return done(std::move(impl));
  failures.push_back(why);
  for (std::size_t i = 0; i < devices.size(); ++i) {
    if (!devices[i].software) continue;
    if (auto impl = try_device(f, devices, i, why)) return done(std::move(impl));
    failures.push_back(why);
  }
  if (devices.empty() && f.query_devices != nullptr) failures.push_back("no EGL devices");
  throw GlUnavailable(kUnavailable + join(failures));
}

}  // namespace nimbus::render
