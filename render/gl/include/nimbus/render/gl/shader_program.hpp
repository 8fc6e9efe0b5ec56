// A linked GLSL program from embedded shader files, with errors that name the file and line, and
// uniforms set by name that must exist: a name no stage declares is an error, never ignored.
#pragma once
#include <epoxy/gl.h>

#include <glm/glm.hpp>
#include <stdexcept>
#include <set>
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

// A uniform set by a name that no stage of the program declares (misspelt, or set on the wrong
// program): a programming error, thrown in every build so that tests catch it.
struct UniformError : std::logic_error {
  using std::logic_error::logic_error;
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
  // True when some stage's source declares `uniform <type> name` outside a block (whether or not
  // the compiler kept it); "name[0]" means the array `name`.
  bool declares(const std::string& name) const;
  // The names every stage declares, as declares() sees them.
  const std::set<std::string>& declared_uniforms() const { return declared_; }

  // glProgramUniform* (no need to use() first). A declared uniform that the compiler dropped
  // (unused in this variant) is skipped; a name no stage declares throws UniformError naming the
  // program's files and the name.
  void set(const char* name, int value) const;
  void set(const char* name, unsigned value) const;
  void set(const char* name, float value) const;
  void set(const char* name, const glm::vec2& value) const;
  void set(const char* name, const glm::vec3& value) const;
  void set(const char* name, const glm::vec4& value) const;
  void set(const char* name, const glm::ivec2& value) const;
  void set(const char* name, const glm::mat4& value) const;

 private:
  ShaderProgram(std::vector<std::string> stage_names, const std::string& defines,
                const std::vector<ShaderFile>& extra_files);
  // The location of `name`, or -1 after checking that it is declared (UniformError if not).
  GLint checked_location(const char* name) const;
  GLuint id_ = 0;
  std::vector<std::string> stage_names_;
  std::set<std::string> declared_;
};

}  // namespace nimbus::render
