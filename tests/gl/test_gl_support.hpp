// One headless GL context shared by every GL test in the process, and a macro that skips a test
// (with the reason) only when no OpenGL 4.5 core context can be created at all.
#pragma once
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "nimbus/render/gl/context.hpp"

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

}  // namespace nimbus::test

// In a TEST body: skips it, naming the reason, when there is no GL 4.5 core context.
#define NIMBUS_REQUIRE_GL()                                                              \
  do {                                                                                   \
    if (!::nimbus::test::shared_gl().context) GTEST_SKIP() << ::nimbus::test::shared_gl().unavailable; \
  } while (0)
