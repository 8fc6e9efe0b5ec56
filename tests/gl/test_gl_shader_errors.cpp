// Broken shader sources give ShaderError naming the right file and line: in the stage file, after
// an include, inside an include, in the defines; link errors name the program's files.
#include <gtest/gtest.h>

#include <string>

#include "nimbus/render/gl/resources.hpp"
#include "nimbus/render/gl/shader_program.hpp"
#include "test_gl_support.hpp"

namespace nimbus::render {
namespace {

// The error must be located at `file`:`line` and what() must begin with that location.
void expect_error_at(const std::vector<ShaderFile>& files, const std::vector<std::string>& stages,
                     const std::string& defines, const std::string& file, int line) {
  try {
    ShaderProgram::from_sources(files, stages, defines);
    ADD_FAILURE() << "no ShaderError for a broken " << file;
  } catch (const ShaderError& e) {
    EXPECT_EQ(e.file, file) << e.what();
    EXPECT_EQ(e.line, line) << e.what();
    const std::string head = file + ":" + std::to_string(line) + ": ";
    EXPECT_EQ(std::string(e.what()).rfind(head, 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("error"), std::string::npos) << e.what();
  }
  check_gl("after a failed compile");
}

const std::string kHelper =  // 5 lines; an undeclared name on line 4 when BREAK_HELPER is set
    "// helper\n"
    "float helper(float x) {\n"
    "#ifdef BREAK_HELPER\n"
    "  return x * undeclared_in_helper;\n"
    "#else\n"
    "  return x;\n"
    "#endif\n"
    "}\n";

TEST(GlShaderErrors, ErrorInTheStageFileNamesItsLine) {
  NIMBUS_REQUIRE_GL();
  const ShaderFile broken{"test_broken.frag.glsl",
                          "// a comment before #version\n"   // 1
                          "#version 450 core\n"              // 2
                          "out vec4 color;\n"                // 3
                          "void main() {\n"                  // 4
                          "  float a = 1.0;\n"               // 5
                          "  color = vec4(a, missing_b);\n"  // 6
                          "}\n"};
  expect_error_at({broken}, {"fullscreen.vert.glsl", "test_broken.frag.glsl"}, "", "shaders/test_broken.frag.glsl",
                  6);
  // Defines before the file do not move its lines.
  expect_error_at({broken}, {"fullscreen.vert.glsl", "test_broken.frag.glsl"}, "#define A 1\n#define B 2\n#define C 3\n",
                  "shaders/test_broken.frag.glsl", 6);
}

TEST(GlShaderErrors, ErrorAfterAnIncludeNamesTheIncludingFile) {
  NIMBUS_REQUIRE_GL();
  const ShaderFile stage{"test_broken.frag.glsl",
                         "#version 450 core\n"                  // 1
                         "#include \"lib/test_helper.glsl\"\n"  // 2
                         "out vec4 color;\n"                    // 3
                         "void main() {\n"                      // 4
                         "  color = vec4(helper(1.0));\n"       // 5
                         "  color += missing_c;\n"              // 6
                         "}\n"};
  const ShaderFile helper{"lib/test_helper.glsl", kHelper};
  expect_error_at({stage, helper}, {"fullscreen.vert.glsl", "test_broken.frag.glsl"}, "",
                  "shaders/test_broken.frag.glsl", 6);
}

TEST(GlShaderErrors, ErrorInsideAnIncludeNamesTheIncludedFile) {
  NIMBUS_REQUIRE_GL();
  const ShaderFile stage{"test_broken.frag.glsl",
                         "#version 450 core\n"
                         "#include \"lib/test_helper.glsl\"\n"
                         "out vec4 color;\n"
                         "void main() { color = vec4(helper(1.0)); }\n"};
  const ShaderFile helper{"lib/test_helper.glsl", kHelper};
  expect_error_at({stage, helper}, {"fullscreen.vert.glsl", "test_broken.frag.glsl"}, "#define BREAK_HELPER\n",
                  "shaders/lib/test_helper.glsl", 4);
}

TEST(GlShaderErrors, ErrorInTheDefinesNamesThem) {
  NIMBUS_REQUIRE_GL();
  expect_error_at(test::test_shader_files(), {"fullscreen.vert.glsl", "test_pattern.frag.glsl"},
                  "#define OK 1\nconst float x = ;\n",
                  "(defines)", 2);
}

TEST(GlShaderErrors, ErrorInAnEmbeddedVertexStageIsFound) {
  NIMBUS_REQUIRE_GL();
  // An in-memory file of an embedded name takes its place: here a broken full-screen vertex stage.
  const ShaderFile vert{"fullscreen.vert.glsl", "#version 450 core\nout vec2 uv;\nvoid main() { uv = 1; }\n"};
  std::vector<ShaderFile> files = test::test_shader_files();
  files.push_back(vert);
  expect_error_at(files, {"fullscreen.vert.glsl", "test_pattern.frag.glsl"}, "", "shaders/fullscreen.vert.glsl", 3);
}

TEST(GlShaderErrors, LinkErrorNamesTheProgramFiles) {
  NIMBUS_REQUIRE_GL();
  // Compiles alone, but the fragment stage reads a varying the vertex stage never writes.
  const ShaderFile frag{"test_unlinked.frag.glsl",
                        "#version 450 core\nin vec3 never_written;\nout vec4 color;\n"
                        "void main() { color = vec4(never_written, 1.0); }\n"};
  try {
    ShaderProgram::from_sources({frag}, {"fullscreen.vert.glsl", "test_unlinked.frag.glsl"});
    FAIL() << "link succeeded";
  } catch (const ShaderError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("linking shaders/fullscreen.vert.glsl + shaders/test_unlinked.frag.glsl failed: ", 0), 0u)
        << what;
    EXPECT_NE(what.find("never_written"), std::string::npos) << what;
  }
}

TEST(GlShaderErrors, BadNamesAreInvalidArguments) {
  NIMBUS_REQUIRE_GL();
  EXPECT_THROW(ShaderProgram({"fullscreen.vert.glsl", "no_such.frag.glsl"}), std::invalid_argument);
  try {
    ShaderProgram({"lib/test_helper.glsl"});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("lib/test_helper.glsl"), std::string::npos);
  }
  EXPECT_THROW(ShaderProgram(std::vector<std::string>{}), std::invalid_argument);
}

}  // namespace
}  // namespace nimbus::render
