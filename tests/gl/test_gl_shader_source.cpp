// Shader expansion without a GL context: #version first, defines after it, includes resolved
// once, cycles and missing files named, and the #line table mapping every line back.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <regex>
#include <sstream>

#include "nimbus/render/gl/shader_source.hpp"

namespace nimbus::render {
namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// Replays the #line directives (GLSL >= 330: the line after "#line N K" is line N of string K)
// and returns, for every expanded line that is not a directive, its (file, line) origin.
struct Origin {
  std::string file;
  int line;
  std::string text;
};
std::vector<Origin> origins(const ExpandedShader& e) {
  static const std::regex line_re(R"(^#line (\d+) (\d+)$)");
  std::vector<Origin> out;
  std::size_t file = 0;
  int line = 1;
  bool first = true;
  for (const std::string& l : lines_of(e.text)) {
    std::smatch m;
    if (std::regex_match(l, m, line_re)) {
      file = std::stoul(m[2].str());
      // Lines of file K are numbered K * kShaderLineBase + N.
      EXPECT_EQ(std::stol(m[1].str()) / kShaderLineBase, static_cast<long>(file)) << l;
      line = static_cast<int>(std::stol(m[1].str()) % kShaderLineBase);
      continue;
    }
    if (first) {  // the #version line: its position in the stage file is not tracked
      first = false;
      continue;
    }
    out.push_back({e.files.at(file), line, l});
    ++line;
  }
  return out;
}

const std::vector<ShaderFile> kFiles = {
    {"t/a.frag.glsl", "// header comment\n#version 450 core\n#include \"b.glsl\"\nint a_line4;\n"
                      "#include \"lib/c.glsl\"\nint a_line6;\n#include \"b.glsl\"\nint a_line8;\n"},
    {"t/b.glsl", "#pragma once\nint b_line2;\n#include \"../lib/c.glsl\"\nint b_line4;\n"},
    {"lib/c.glsl", "int c_line1;\nint c_line2;\n"},
    {"cyc/x.frag.glsl", "#version 450 core\n#include \"y.glsl\"\n"},
    {"cyc/y.glsl", "\n#include \"z.glsl\"\n"},
    {"cyc/z.glsl", "#include \"y.glsl\"\n"},
    {"miss.frag.glsl", "#version 450 core\n\n#include \"nowhere.glsl\"\n"},
    {"cpp.frag.glsl", "#version 450 core\n#ifdef __cplusplus\n#include \"glm/glm.hpp\"\n#endif\n"},
};

TEST(GlShaderSource, VersionFirstDefinesNextEveryLineTraced) {
  const ExpandedShader e = expand_shader("t/a.frag.glsl", "#define STEPS 64\n#define FAST", kFiles);
  const auto lines = lines_of(e.text);
  ASSERT_GE(lines.size(), 2u);
  EXPECT_EQ(lines[0], "#version 450 core");
  ASSERT_EQ(e.files, (std::vector<std::string>{"t/a.frag.glsl", "(defines)", "t/b.glsl", "lib/c.glsl"}));

  // Every marker "int NAME_lineN;" must trace back to its own file and line N.
  const std::map<std::string, std::string> prefix_file = {
      {"a", "t/a.frag.glsl"}, {"b", "t/b.glsl"}, {"c", "lib/c.glsl"}};
  static const std::regex marker_re(R"(^int ([abc])_line(\d+);$)");
  int markers = 0;
  std::map<std::string, int> count;
  for (const Origin& o : origins(e)) {
    std::smatch m;
    if (o.text == "#define STEPS 64") {
      EXPECT_EQ(o.file, "(defines)");
      EXPECT_EQ(o.line, 1);
    }
    if (o.text == "#define FAST") {
      EXPECT_EQ(o.line, 2);  // a missing final newline is supplied
    }
    if (o.text == "// header comment") {
      EXPECT_EQ(o.file, "t/a.frag.glsl");
      EXPECT_EQ(o.line, 1);
    }
    if (!std::regex_match(o.text, m, marker_re)) continue;
    ++markers;
    ++count[o.text];
    EXPECT_EQ(o.file, prefix_file.at(m[1].str())) << o.text;
    EXPECT_EQ(o.line, std::stoi(m[2].str())) << o.text;
  }
  // a: 3 markers; b and c included once although named twice each.
  EXPECT_EQ(markers, 3 + 2 + 2);
  for (const auto& [text, n] : count) EXPECT_EQ(n, 1) << text;
  EXPECT_EQ(e.text.find("#pragma once"), std::string::npos);
  EXPECT_EQ(e.text.find("#include"), std::string::npos);
}

TEST(GlShaderSource, NoDefinesNoDefinesEntry) {
  const ExpandedShader e = expand_shader("t/a.frag.glsl", "", kFiles);
  EXPECT_EQ(e.files, (std::vector<std::string>{"t/a.frag.glsl", "t/b.glsl", "lib/c.glsl"}));
  for (const Origin& o : origins(e)) {
    if (o.text == "int c_line2;") {
      EXPECT_EQ(o.line, 2);
    }
  }
}

TEST(GlShaderSource, CycleIsAnErrorNamingTheChain) {
  try {
    expand_shader("cyc/x.frag.glsl", "", kFiles);
    FAIL() << "cycle accepted";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("shaders/cyc/z.glsl:1: "), std::string::npos) << what;
    EXPECT_NE(what.find("cyc/x.frag.glsl -> cyc/y.glsl -> cyc/z.glsl -> cyc/y.glsl"), std::string::npos) << what;
  }
}

TEST(GlShaderSource, MissingIncludeAndUnknownNamesAreNamed) {
  try {
    expand_shader("miss.frag.glsl", "", kFiles);
    FAIL() << "missing include accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("shaders/miss.frag.glsl:3: #include \"nowhere.glsl\""), std::string::npos)
        << e.what();
  }
  try {
    expand_shader("no_such.frag.glsl");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no_such.frag.glsl"), std::string::npos);
  }
  EXPECT_THROW(shader_text("lib/no_such.glsl"), std::invalid_argument);
}

TEST(GlShaderSource, NonGlslIncludesAreLeftForThePreprocessor) {
  // Shared GLSL/C++ headers may include C++ headers under #ifdef __cplusplus.
  const ExpandedShader e = expand_shader("cpp.frag.glsl", "", kFiles);
  EXPECT_NE(e.text.find("#include \"glm/glm.hpp\""), std::string::npos);
}

TEST(GlShaderSource, EmbeddedShadersAreListedAndReadable) {
  const auto names = shader_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "fullscreen.vert.glsl"), names.end());
  for (const auto& n : names) {
    EXPECT_FALSE(shader_text(n).empty()) << n;
    EXPECT_EQ(n.find("shaders/"), std::string::npos) << n;  // names are relative to shaders/
  }
}

TEST(GlShaderSource, LogLocationsMapToFiles) {
  const std::vector<std::string> files = {"a.frag.glsl", "(defines)", "lib/x.glsl"};
  // Mesa, NVIDIA and glslang formats; an unparseable line is kept.
  EXPECT_EQ(map_shader_log("2:12(5): error: `foo' undeclared", files),
            "shaders/lib/x.glsl:12: error: `foo' undeclared");
  EXPECT_EQ(map_shader_log("0(7) : error C1008: undefined variable \"foo\"", files),
            "shaders/a.frag.glsl:7: error C1008: undefined variable \"foo\"");
  EXPECT_EQ(map_shader_log("ERROR: 1:1: 'x' : syntax error", files), "(defines):1: error: 'x' : syntax error");
  EXPECT_EQ(map_shader_log("linker says no\n0:3(1): warning: w", files),
            "linker says no\nshaders/a.frag.glsl:3: warning: w");
  EXPECT_EQ(map_shader_log("9:1(1): error: e", files), "<source 9>:1: error: e");
  // A line number >= kShaderLineBase names its file whatever source string is reported (Mesa
  // reports 0 for errors inside expressions).
  EXPECT_EQ(map_shader_log("0:200004(13): error: `u' undeclared", files), "shaders/lib/x.glsl:4: error: `u' undeclared");
  EXPECT_EQ(map_shader_log("ERROR: 2:200017: 'u' : undeclared identifier", files),
            "shaders/lib/x.glsl:17: error: 'u' : undeclared identifier");
}

}  // namespace
}  // namespace nimbus::render
