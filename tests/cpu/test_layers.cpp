// The layer checker (cmake/check_layers.cmake), which the build runs over the source tree: it
// passes a tree that keeps the rules and fails, naming the file and the include, on one that
// includes a higher layer or OpenGL from a CPU layer.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/run_nimbus.hpp"

namespace nimbus::test {
namespace {

namespace fs = std::filesystem;

class Tree {
 public:
  Tree() {
    char tmpl[] = "/tmp/nimbus_layers_XXXXXX";
    if (const char* made = mkdtemp(tmpl)) root_ = made;
  }
  ~Tree() {
    std::error_code ec;
    if (!root_.empty()) fs::remove_all(root_, ec);
  }
  void write(const std::string& rel, const std::string& text) const {
    fs::create_directories((root_ / rel).parent_path());
    std::ofstream(root_ / rel) << text;
  }
  RunResult check() const {
    return run_command(std::string(NIMBUS_CMAKE_COMMAND) + " -DROOT=" + root_.string() + " -P " + NIMBUS_SOURCE_DIR +
                       "/cmake/check_layers.cmake");
  }
  bool ok() const { return !root_.empty(); }

 private:
  fs::path root_;
};

TEST(Layers, ATreeThatKeepsTheRulesPasses) {
  Tree t;
  ASSERT_TRUE(t.ok());
  t.write("base/src/a.cpp", "#include \"nimbus/base/memory.hpp\"\n");
  t.write("render/core/src/b.cpp", "#include \"nimbus/volume/vdb_read.hpp\"\n#include <glm/glm.hpp>\n");
  t.write("render/gl/src/c.cpp", "#include <epoxy/gl.h>\n#include \"nimbus/render/core/camera.hpp\"\n");
  t.write("render/frame/src/d.cpp", "#include \"nimbus/render/clouds/cloud_renderer.hpp\"\n");
  t.write("samples/app/src/e.cpp", "#include \"nimbus/render/reference/cloud_reference.hpp\"\n");
  const RunResult r = t.check();
  EXPECT_EQ(r.code, 0) << r.output;
}

TEST(Layers, GlInACpuLayerOrAnIncludeUpwardsFailsNamingTheFile) {
  Tree t;
  ASSERT_TRUE(t.ok());
  t.write("base/src/a.cpp", "\n");
  t.write("render/reference/src/bad_gl.cpp", "#include <epoxy/gl.h>\n");
  t.write("render/core/include/nimbus/render/core/bad_up.hpp", "#include \"nimbus/render/gl/context.hpp\"\n");
  t.write("render/clouds/src/bad_side.cpp", "#include \"nimbus/render/shafts/shaft_renderer.hpp\"\n");
  t.write("render/image/src/bad_egl.cpp", "  #  include <EGL/egl.h>\n");
  // The app library is CPU-only (the CPU tests link it): no GL layer, no GL header.
  t.write("samples/app/src/bad_app.cpp", "#include \"nimbus/render/frame/frame_renderer.hpp\"\n#include <GL/gl.h>\n");
  const RunResult r = t.check();
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("render/reference/src/bad_gl.cpp: includes epoxy/gl.h"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("bad_up.hpp: includes nimbus/render/gl/context.hpp"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("bad_side.cpp: includes nimbus/render/shafts/shaft_renderer.hpp"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("bad_egl.cpp: includes EGL/egl.h"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("bad_app.cpp: includes nimbus/render/frame/frame_renderer.hpp"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("bad_app.cpp: includes GL/gl.h"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace nimbus::test
