// A linked GLSL program from embedded shader files, with errors that name the file and line.
#pragma once
#include <epoxy/gl.h>

#include <glm/glm.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "nimbus/render/gl/shader_source.hpp"

namespace nimbus::render {

// A compile or link failure. what() starts with "shaders/<file>:<line>: <driver message>" for a
// compile error (every mapped log line follows, one per line) and names the program's files
// for a link error. file/line: the first located error (empty/0 when the log has none).
struct ShaderError : std::runtime_error {
  ShaderError(const std::string& message, std::string error_file, int error_line)
      : std::runtime_error(message), file(std::move(error_file)), line(error_line) {}
  std::string file;  // e.g. "shaders/lib/airlight.glsl"
  int line = 0;
};

// The stage of a file from its suffix: .vert.glsl, .frag.glsl, .geom.glsl, .comp.glsl
// (GL_VERTEX_SHADER, ...). Other names -> std::invalid_argument naming the file.
GLenum shader_stage(const std::string& name);

// A compiled shader object of one stage (tests compile every embedded stage alone with it).
// Returns the shader id (caller deletes it) or throws ShaderError.
GLuint compile_shader_stage(const std::string& name, const std::string& defines = "",
                            const std::vector<ShaderFile>& extra_files = {});

// Move-only; deletes the program. Needs a current GL context.
class ShaderProgram {
 public:
  // One file per stage, e.g. {"fullscreen.vert.glsl", "shafts.frag.glsl"}; `defines` goes into
  // every stage. Throws ShaderError, or std::invalid_argument for an unknown name or stage.
  explicit ShaderProgram(std::vector<std::string> stage_names, const std::string& defines = "");

  // The same from sources given as strings (looked up before the embedded files): for tests.
  static ShaderProgram from_sources(const std::vector<ShaderFile>& files,
                                    std::vector<std::string> stage_names,
                                    const std::string& defines = "");

  ShaderProgram(ShaderProgram&& other) noexcept;
  ShaderProgram& operator=(ShaderProgram&& other) noexcept;
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;
  ~ShaderProgram();

  GLuint id() const { return id_; }
  const std::vector<std::string>& stage_names() const { return stage_names_; }
  void use() const;
  // -1 when the program has no active uniform of that name (unused ones are optimised away).
  GLint uniform_location(const char* name) const;
  bool has_uniform(const char* name) const { return uniform_location(name) >= 0; }

  // glProgramUniform* (no need to use() first); a name with no active uniform is ignored.
  void set(const char* name, int value) const;
  void set(const char* name, float value) const;
  void set(const char* name, const glm::vec2& value) const;
  void set(const char* name, const glm::vec3& value) const;
  void set(const char* name, const glm::vec4& value) const;
  void set(const char* name, const glm::ivec2& value) const;
  void set(const char* name, const glm::mat4& value) const;

 private:
  ShaderProgram(std::vector<std::string> stage_names, const std::string& defines,
                const std::vector<ShaderFile>& extra_files);
  GLuint id_ = 0;
  std::vector<std::string> stage_names_;
};

}  // namespace nimbus::render
