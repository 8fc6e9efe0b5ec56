// One headless GL context shared by every GL test in the process, and a macro that skips a test
// (with the reason) only when no OpenGL 4.5 core context can be created at all.
#pragma once
#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "nimbus/render/gl/context.hpp"
#include "nimbus/render/gl/shader_source.hpp"

namespace nimbus::test {

struct SharedGl {
  std::unique_ptr<render::GlContext> context;
  std::string unavailable;  // GlUnavailable::what() when context is null
};

inline SharedGl& shared_gl() {
  static SharedGl gl = [] {
    SharedGl g;
    try {
      g.context = render::GlContext::create_headless();
    } catch (const render::GlUnavailable& e) {
      g.unavailable = e.what();
    }
    return g;
  }();
  if (gl.context) gl.context->make_current();  // another test may have made its own current
  return gl;
}

// The test-only shaders (tests/gl/shaders/, not shipped in the program), read from the source
// tree, for ShaderProgram::from_sources: test_pattern.frag.glsl (each pixel's coordinates and a
// uniform through test_lib.glsl) and test_uniforms.frag.glsl (every setter's value, written out).
inline std::vector<render::ShaderFile> test_shader_files() {
  std::vector<render::ShaderFile> files;
  for (const char* name : {"test_lib.glsl", "test_pattern.frag.glsl", "test_uniforms.frag.glsl"}) {
    std::ifstream in(std::string(NIMBUS_SOURCE_DIR) + "/tests/gl/shaders/" + name);
    std::ostringstream text;
    text << in.rdbuf();
    files.push_back({name, text.str()});
  }
  return files;
}

}  // namespace nimbus::test

// In a TEST body: skips it, naming the reason, when there is no GL 4.5 core context.
#define NIMBUS_REQUIRE_GL()                                                              \
  do {                                                                                   \
    if (!::nimbus::test::shared_gl().context) GTEST_SKIP() << ::nimbus::test::shared_gl().unavailable; \
  } while (0)
