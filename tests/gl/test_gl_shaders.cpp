// Every embedded stage shader, expanded, passes glslangValidator and compiles on the GL context;
// every fragment stage links with its partner stages (docs/gl.md: X.vert.glsl and X.geom.glsl
// when they exist, else fullscreen.vert.glsl); compute stages and lone vertex stages link alone.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "nimbus/render/gl/resources.hpp"
#include "nimbus/render/gl/shader_program.hpp"
#include "nimbus/render/gl/shader_source.hpp"
#include "support/run_nimbus.hpp"
#include "test_gl_support.hpp"

namespace nimbus::render {
namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

bool is_stage(const std::string& name) {
  for (const char* s : {".vert.glsl", ".frag.glsl", ".geom.glsl", ".comp.glsl"}) {
    if (ends_with(name, s)) return true;
  }
  return false;
}

std::vector<std::string> stage_files() {
  std::vector<std::string> out;
  for (const auto& n : shader_names()) {
    if (is_stage(n)) out.push_back(n);
  }
  return out;
}

bool embedded(const std::string& name) {
  const auto names = shader_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::string stem(const std::string& name) { return name.substr(0, name.size() - std::string(".frag.glsl").size()); }

const char* glslang_stage(const std::string& name) {
  if (ends_with(name, ".vert.glsl")) return "vert";
  if (ends_with(name, ".frag.glsl")) return "frag";
  if (ends_with(name, ".geom.glsl")) return "geom";
  return "comp";
}

// A temporary folder removed with its files at the end of the scope.
class TempDir {
 public:
  TempDir() {
    char tmpl[] = "/tmp/nimbus_glsl_XXXXXX";
    const char* made = mkdtemp(tmpl);
    if (made != nullptr) path_ = made;
  }
  ~TempDir() {
    for (const auto& f : files_) std::remove(f.c_str());
    if (!path_.empty()) rmdir(path_.c_str());
  }
  std::string write(const std::string& name, const std::string& text) {
    const std::string p = path_ + "/" + name;
    std::ofstream(p) << text;
    files_.push_back(p);
    return p;
  }
  bool ok() const { return !path_.empty(); }

 private:
  std::string path_;
  std::vector<std::string> files_;
};

TEST(GlShaders, ThereAreStagesToCheck) {
  const auto stages = stage_files();
  EXPECT_NE(std::find(stages.begin(), stages.end(), "fullscreen.vert.glsl"), stages.end());
  EXPECT_NE(std::find(stages.begin(), stages.end(), "cloud_slice.frag.glsl"), stages.end());
  // The program ships no test fixture: those live in tests/gl/shaders/.
  for (const auto& n : shader_names()) EXPECT_NE(n.rfind("test_", 0), 0u) << n << " is embedded in the program";
}

TEST(GlShaders, EveryStagePassesGlslangValidator) {
  const test::RunResult version = test::run_command("glslangValidator --version");
  ASSERT_EQ(version.code, 0) << "glslangValidator not runnable (scripts/install-deps.sh installs glslang-tools): "
                             << version.output;
  TempDir dir;
  ASSERT_TRUE(dir.ok());
  int index = 0;
  for (const std::string& name : stage_files()) {
    const ExpandedShader e = expand_shader(name);
    const std::string file = dir.write("stage" + std::to_string(index++) + ".glsl", e.text);
    const test::RunResult r =
        test::run_command(std::string("glslangValidator -S ") + glslang_stage(name) + " '" + file + "'");
    EXPECT_EQ(r.code, 0) << "shaders/" << name << " fails glslangValidator:\n" << map_shader_log(r.output, e.files);
  }
}

TEST(GlShaders, EveryStageCompilesOnTheContext) {
  NIMBUS_REQUIRE_GL();
  for (const std::string& name : stage_files()) {
    try {
      const GLuint shader = compile_shader_stage(name);
      glDeleteShader(shader);
    } catch (const ShaderError& e) {
      ADD_FAILURE() << e.what();
    }
  }
  check_gl("compiling every stage");
}

TEST(GlShaders, EveryProgramLinks) {
  NIMBUS_REQUIRE_GL();
  std::vector<std::vector<std::string>> programs;
  std::vector<std::string> paired;  // vertex/geometry stages linked with some fragment stage
  for (const std::string& name : stage_files()) {
    if (ends_with(name, ".comp.glsl")) {
      programs.push_back({name});
    } else if (ends_with(name, ".frag.glsl")) {
      const std::string vert = stem(name) + ".vert.glsl", geom = stem(name) + ".geom.glsl";
      std::vector<std::string> p = {embedded(vert) ? vert : "fullscreen.vert.glsl"};
      if (embedded(geom)) p.push_back(geom);
      p.push_back(name);
      paired.insert(paired.end(), p.begin(), p.end() - 1);
      programs.push_back(p);
    }
  }
  for (const std::string& name : stage_files()) {
    if (!ends_with(name, ".vert.glsl") || std::find(paired.begin(), paired.end(), name) != paired.end()) continue;
    const std::string geom = name.substr(0, name.size() - std::string(".vert.glsl").size()) + ".geom.glsl";
    programs.push_back(embedded(geom) ? std::vector<std::string>{name, geom} : std::vector<std::string>{name});
  }
  for (const auto& stages : programs) {
    try {
      ShaderProgram program(stages);
      EXPECT_NE(program.id(), 0u);
    } catch (const ShaderError& e) {
      ADD_FAILURE() << e.what();
    }
  }
  check_gl("linking every program");
}

}  // namespace
}  // namespace nimbus::render
