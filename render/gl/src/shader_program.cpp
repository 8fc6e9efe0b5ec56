// Compiling expanded shader files and linking programs; info logs mapped back to shaders/ files.
#include "nimbus/render/gl/shader_program.hpp"

#include <algorithm>
#include <cstring>
#include <glm/gtc/type_ptr.hpp>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace nimbus::render {
namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string shader_log(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  log.resize(std::strlen(log.c_str()));
  return log;
}

std::string program_log(GLuint program) {
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  glGetProgramInfoLog(program, length, nullptr, log.data());
  log.resize(std::strlen(log.c_str()));
  return log;
}

// The first "shaders/<file>:<line>: " location in a mapped log, preferring an error line.
void first_location(const std::string& mapped, std::string& file, int& line) {
  static const std::regex loc_re(R"(^((?:shaders/[^:\s]+)|\(defines\)):(\d+): (.*)$)");
  std::istringstream in(mapped);
  std::string text;
  bool found = false;
  while (std::getline(in, text)) {
    std::smatch m;
    if (!std::regex_match(text, m, loc_re)) continue;
    const bool is_error = m[3].str().find("error") != std::string::npos;
    if (!found || is_error) {
      file = m[1].str();
      line = std::stoi(m[2].str());
      found = true;
      if (is_error) return;
    }
  }
}

std::string join_paths(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : " + ") + shader_display_path(n);
  return out;
}

// The names of the uniforms declared outside blocks in an expanded stage: "uniform TYPE NAME;"
// and "uniform TYPE NAME[N];", layout qualifiers and precision allowed, comments ignored.
void collect_uniform_names(const std::string& text, std::set<std::string>& names) {
  static const std::regex decl_re(
      R"(\buniform\s+(?:(?:lowp|mediump|highp)\s+)?[A-Za-z_]\w*\s+([A-Za-z_]\w*)\s*(?:\[[^\]]*\])?\s*;)");
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const auto comment = line.find("//");
    if (comment != std::string::npos) line.resize(comment);
    for (std::sregex_iterator it(line.begin(), line.end(), decl_re), end; it != end; ++it) names.insert((*it)[1].str());
  }
}

}  // namespace

GLenum shader_stage(const std::string& name) {
  if (ends_with(name, ".vert.glsl")) return GL_VERTEX_SHADER;
  if (ends_with(name, ".frag.glsl")) return GL_FRAGMENT_SHADER;
  if (ends_with(name, ".geom.glsl")) return GL_GEOMETRY_SHADER;
  if (ends_with(name, ".comp.glsl")) return GL_COMPUTE_SHADER;
  throw std::invalid_argument("shader '" + name +
                              "' has no stage suffix (.vert.glsl, .frag.glsl, .geom.glsl, .comp.glsl)");
}

GLuint compile_shader_stage(const std::string& name, const std::string& defines,
                            const std::vector<ShaderFile>& extra_files) {
  const GLenum stage = shader_stage(name);
  const ExpandedShader src = expand_shader(name, defines, extra_files);
  const GLuint shader = glCreateShader(stage);
  if (shader == 0) throw ShaderError("glCreateShader failed for " + shader_display_path(name), "", 0);
  const char* text = src.text.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok == GL_TRUE) return shader;
  const std::string mapped = map_shader_log(shader_log(shader), src.files);
  glDeleteShader(shader);
  std::string file;
  int line = 0;
  first_location(mapped, file, line);
  std::string message = mapped.empty() ? shader_display_path(name) + ": compile failed with an empty log" : mapped;
  // Put the first error line first, so a one-line report names it.
  if (!file.empty()) {
    const std::string head = file + ":" + std::to_string(line) + ": ";
    const auto at = message.find(head);
    if (at != 0 && at != std::string::npos) {
      const auto end = message.find('\n', at);
      const std::string first = message.substr(at, end == std::string::npos ? std::string::npos : end - at);
      message = first + "\n" + message;
    }
  }
  throw ShaderError(message, file, line);
}

ShaderProgram::ShaderProgram(std::vector<std::string> stage_names, const std::string& defines)
    : ShaderProgram(std::move(stage_names), defines, {}) {}

ShaderProgram ShaderProgram::from_sources(const std::vector<ShaderFile>& files, std::vector<std::string> stage_names,
                                          const std::string& defines) {
  return ShaderProgram(std::move(stage_names), defines, files);
}

ShaderProgram::ShaderProgram(std::vector<std::string> stage_names, const std::string& defines,
                             const std::vector<ShaderFile>& extra_files)
    : stage_names_(std::move(stage_names)) {
  if (stage_names_.empty()) throw std::invalid_argument("shader program: no stage files given");
  for (const auto& n : stage_names_) shader_stage(n);  // unknown suffix -> invalid_argument first
  std::vector<GLuint> shaders;
  const auto delete_shaders = [&] {
    for (GLuint s : shaders) glDeleteShader(s);
  };
  try {
    for (const auto& n : stage_names_) {
      shaders.push_back(compile_shader_stage(n, defines, extra_files));
      collect_uniform_names(expand_shader(n, defines, extra_files).text, declared_);
    }
  } catch (...) {
    delete_shaders();
    throw;
  }
  id_ = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(id_, s);
  glLinkProgram(id_);
  for (GLuint s : shaders) glDetachShader(id_, s);
  delete_shaders();
  GLint ok = GL_FALSE;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = program_log(id_);
    glDeleteProgram(id_);
    id_ = 0;
    throw ShaderError("linking " + join_paths(stage_names_) + " failed: " + log, "", 0);
  }
}

ShaderProgram::ShaderProgram(ShaderProgram&& other) noexcept
    : id_(std::exchange(other.id_, 0)),
      stage_names_(std::move(other.stage_names_)),
      declared_(std::move(other.declared_)) {}

ShaderProgram& ShaderProgram::operator=(ShaderProgram&& other) noexcept {
  if (this != &other) {
    if (id_ != 0) glDeleteProgram(id_);
    id_ = std::exchange(other.id_, 0);
    stage_names_ = std::move(other.stage_names_);
    declared_ = std::move(other.declared_);
  }
  return *this;
}

ShaderProgram::~ShaderProgram() {
  if (id_ != 0) glDeleteProgram(id_);
}

void ShaderProgram::use() const { glUseProgram(id_); }

GLint ShaderProgram::uniform_location(const char* name) const { return glGetUniformLocation(id_, name); }

bool ShaderProgram::declares(const std::string& name) const {
  return declared_.count(name.substr(0, name.find('['))) > 0;
}

GLint ShaderProgram::checked_location(const char* name) const {
  const GLint loc = uniform_location(name);
  if (loc < 0 && !declares(name))
    throw UniformError(join_paths(stage_names_) + ": no stage declares uniform '" + name +
                       "' (misspelt, or set on the wrong program)");
  return loc;
}

void ShaderProgram::set(const char* name, int value) const {
  if (const GLint loc = checked_location(name); loc >= 0) glProgramUniform1i(id_, loc, value);
}
void ShaderProgram::set(const char* name, unsigned value) const {
  if (const GLint loc = checked_location(name); loc >= 0) glProgramUniform1ui(id_, loc, value);
}
void ShaderProgram::set(const char* name, float value) const {
  if (const GLint loc = checked_location(name); loc >= 0) glProgramUniform1f(id_, loc, value);
}
void ShaderProgram::set(const char* name, const glm::vec2& value) const {
  if (const GLint loc = checked_location(name); loc >= 0) glProgramUniform2fv(id_, loc, 1, glm::value_ptr(value));
}
void ShaderProgram::set(const char* name, const glm::vec3& value) const {
  if (const GLint loc = checked_location(name); loc >= 0) glProgramUniform3fv(id_, loc, 1, glm::value_ptr(value));
}
void ShaderProgram::set(const char* name, const glm::vec4& value) const {
  if (const GLint loc = checked_location(name); loc >= 0) glProgramUniform4fv(id_, loc, 1, glm::value_ptr(value));
}
void ShaderProgram::set(const char* name, const glm::ivec2& value) const {
  if (const GLint loc = checked_location(name); loc >= 0) glProgramUniform2iv(id_, loc, 1, glm::value_ptr(value));
}
void ShaderProgram::set(const char* name, const glm::mat4& value) const {
  if (const GLint loc = checked_location(name); loc >= 0)
    glProgramUniformMatrix4fv(id_, loc, 1, GL_FALSE, glm::value_ptr(value));
}

}  // namespace nimbus::render
