// The GLSL sources built into the binary (shaders/**/*.glsl) and their expansion: defines after
// #version, "lib/x.glsl" includes resolved, #line directives that map driver messages back.
#pragma once
#include <string>
#include <vector>

namespace nimbus::render {

// Every embedded shader, by its path relative to shaders/ ("fullscreen.vert.glsl", "lib/x.glsl").
std::vector<std::string> shader_names();

// The raw text of an embedded shader. Unknown name -> std::invalid_argument naming it.
std::string shader_text(const std::string& name);

// A source given as a string (tests, tools); found before the embedded files of the same name.
struct ShaderFile {
  std::string name;  // path relative to shaders/, e.g. "test_broken.frag.glsl"
  std::string text;
};

// Shader files that take precedence over the embedded ones for every program compiled from now
// on (the viewer's F5 reload from a source tree); empty: the embedded files. Process-wide.
void set_shader_overrides(std::vector<ShaderFile> files);
std::vector<ShaderFile> shader_overrides();
// Every embedded shader's name read from `dir` (dir/<name>); names missing there are left out.
// std::runtime_error naming a file that exists but cannot be read.
std::vector<ShaderFile> read_shader_dir(const std::string& dir);

// Lines of files[K] are numbered K * kShaderLineBase + N in the expanded text ("#line
// K*100000+N K"; the stage file, K = 0, keeps its own numbers): Mesa reports source string 0
// for errors inside expressions, whatever #line said, so the line number alone must tell the file.
inline constexpr int kShaderLineBase = 100000;

struct ExpandedShader {
  std::string text;                // ready for glShaderSource
  std::vector<std::string> files;  // files[K] is source-string number K in "#line N K"
};

// The stage file's #version line first, then `defines` (e.g. "#define STEPS 64\n", named
// "(defines)" in `files`), then the file with every `#include "x.glsl"` replaced by that file
// (relative to the including file's folder first, then to shaders/; each file included once,
// a cycle or a missing file -> std::invalid_argument). Only includes ending in .glsl are
// resolved; `#pragma once` lines are blanked. Unknown name -> std::invalid_argument naming it.
ExpandedShader expand_shader(const std::string& name, const std::string& defines = "");
ExpandedShader expand_shader(const std::string& name, const std::string& defines,
                             const std::vector<ShaderFile>& extra_files);

// A driver's or glslangValidator's info log with every "K:LINE" / "K(LINE)" location rewritten
// as "shaders/<file>:<line>: message" (Mesa "0:12(5): error: ...", NVIDIA "0(12) : error ...",
// glslang/AMD "ERROR: 0:12: ..."); LINE >= kShaderLineBase names its file itself. Lines it cannot
// parse are kept as they are.
std::string map_shader_log(const std::string& log, const std::vector<std::string>& files);

// The display path of files[k]: "shaders/<name>", or "(defines)" for the defines.
std::string shader_display_path(const std::string& file);

}  // namespace nimbus::render
