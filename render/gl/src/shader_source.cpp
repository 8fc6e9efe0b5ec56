// Embedded GLSL lookup, #include expansion with a #line table, and info-log location mapping.
#include "nimbus/render/gl/shader_source.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <cstddef>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace nimbus::render {

// Defined in the generated shaders_embedded.cpp (shaders/cmake_embed_shaders.cmake).
struct EmbeddedShader {
  const char* name;
  const char* text;
};
extern const EmbeddedShader kEmbeddedShaders[];
extern const std::size_t kEmbeddedShaderCount;

namespace {

constexpr const char* kDefinesName = "(defines)";

const char* find_embedded(const std::string& name) {
  for (std::size_t i = 0; i < kEmbeddedShaderCount; ++i) {
    if (name == kEmbeddedShaders[i].name) return kEmbeddedShaders[i].text;
  }
  return nullptr;
}

std::mutex& overrides_mutex() {
  static std::mutex m;
  return m;
}
std::vector<ShaderFile>& overrides() {
  static std::vector<ShaderFile> files;
  return files;
}

const std::string* find_text(const std::string& name, const std::vector<ShaderFile>& extra,
                             std::string& storage) {
  for (const auto& f : extra) {
    if (f.name == name) return &f.text;
  }
  {
    std::lock_guard<std::mutex> lock(overrides_mutex());
    for (const auto& f : overrides()) {
      if (f.name == name) {
        storage = f.text;
        return &storage;
      }
    }
  }
  if (const char* t = find_embedded(name)) {
    storage = t;
    return &storage;
  }
  return nullptr;
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

// "a/b/c.glsl" -> "a/b/"; "c.glsl" -> "".
std::string folder_of(const std::string& name) {
  const auto slash = name.rfind('/');
  return slash == std::string::npos ? std::string() : name.substr(0, slash + 1);
}

// Collapses "x/../" and "./" so includes relative to a folder find their embedded name.
std::string normalise(const std::string& path) {
  std::vector<std::string> parts;
  std::stringstream ss(path);
  std::string part;
  while (std::getline(ss, part, '/')) {
    if (part.empty() || part == ".") continue;
    if (part == ".." && !parts.empty() && parts.back() != "..") {
      parts.pop_back();
    } else {
      parts.push_back(part);
    }
  }
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : "/") + p;
  return out;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// "#line N' K" where N' = K * kShaderLineBase + line (see shader_source.hpp).
std::string line_directive(int line, std::size_t index) {
  const long long n = static_cast<long long>(index) * kShaderLineBase + line;
  return "#line " + std::to_string(n) + " " + std::to_string(index) + "\n";
}

class Expander {
 public:
  Expander(const std::vector<ShaderFile>& extra) : extra_(extra) {}

  ExpandedShader run(const std::string& name, const std::string& defines) {
    std::string storage;
    const std::string* text = find_text(name, extra_, storage);
    if (text == nullptr) throw std::invalid_argument("unknown shader '" + name + "'");
    const std::vector<std::string> lines = split_lines(*text);
    static const std::regex version_re(R"(^\s*#\s*version\b.*$)");
    std::size_t version_line = lines.size();
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (std::regex_match(lines[i], version_re)) {
        version_line = i;
        break;
      }
    }
    if (version_line == lines.size()) {
      throw std::invalid_argument("shader '" + name + "' has no #version line");
    }
    out_.files.push_back(name);  // index 0: the stage file
    out_.text += lines[version_line] + "\n";
    if (!defines.empty()) {
      out_.files.push_back(kDefinesName);
      out_.text += line_directive(1, 1) + defines;
      if (defines.back() != '\n') out_.text += "\n";
    }
    seen_.push_back(name);
    emit(name, lines, 0, version_line);
    return std::move(out_);
  }

 private:
  // Appends `lines` of file `index`, recursing into includes; `skip` is a line to blank.
  void emit(const std::string& name, const std::vector<std::string>& lines, std::size_t index, std::size_t skip) {
    static const std::regex include_re(R"re(^\s*#\s*include\s+"([^"]+)"\s*(//.*)?$)re");
    static const std::regex pragma_once_re(R"(^\s*#\s*pragma\s+once\s*$)");
    static const std::regex version_re(R"(^\s*#\s*version\b.*$)");
    if (lines.size() >= static_cast<std::size_t>(kShaderLineBase)) {
      throw std::invalid_argument("shader '" + name + "' has " + std::to_string(lines.size()) + " lines (at most " +
                                  std::to_string(kShaderLineBase - 1) + ")");
    }
    stack_.push_back(name);
    out_.text += line_directive(1, index);
    for (std::size_t i = 0; i < lines.size(); ++i) {
      std::smatch m;
      if (i == skip || std::regex_match(lines[i], pragma_once_re) ||
          (index != 0 && std::regex_match(lines[i], version_re))) {
        out_.text += "\n";
      } else if (std::regex_match(lines[i], m, include_re) && ends_with(m[1].str(), ".glsl")) {
        include(name, m[1].str(), static_cast<int>(i + 1));
        // Back in this file: the next line is i + 2.
        out_.text += line_directive(static_cast<int>(i + 2), index);
      } else {
        out_.text += lines[i] + "\n";
      }
    }
    stack_.pop_back();
  }

  void include(const std::string& from, const std::string& target, int line) {
    std::string storage;
    std::string resolved;
    const std::string* text = nullptr;
    for (const std::string& candidate : {normalise(folder_of(from) + target), normalise(target)}) {
      if ((text = find_text(candidate, extra_, storage)) != nullptr) {
        resolved = candidate;
        break;
      }
    }
    const std::string where = "shaders/" + from + ":" + std::to_string(line) + ": ";
    if (text == nullptr) throw std::invalid_argument(where + "#include \"" + target + "\": no such shader file");
    if (std::find(stack_.begin(), stack_.end(), resolved) != stack_.end()) {
      std::string cycle;
      for (const auto& s : stack_) cycle += s + " -> ";
      throw std::invalid_argument(where + "#include cycle: " + cycle + resolved);
    }
    if (std::find(seen_.begin(), seen_.end(), resolved) != seen_.end()) {
      out_.text += "\n";  // already included once: keeps the line count
      return;
    }
    seen_.push_back(resolved);
    out_.files.push_back(resolved);
    const std::size_t index = out_.files.size() - 1;
    emit(resolved, split_lines(*text), index, static_cast<std::size_t>(-1));
  }

  const std::vector<ShaderFile>& extra_;
  ExpandedShader out_;
  std::vector<std::string> stack_;  // files being expanded, outermost first
  std::vector<std::string> seen_;   // files already included
};

}  // namespace

std::vector<std::string> shader_names() {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < kEmbeddedShaderCount; ++i) names.emplace_back(kEmbeddedShaders[i].name);
  return names;
}

void set_shader_overrides(std::vector<ShaderFile> files) {
  std::lock_guard<std::mutex> lock(overrides_mutex());
  overrides() = std::move(files);
}

std::vector<ShaderFile> shader_overrides() {
  std::lock_guard<std::mutex> lock(overrides_mutex());
  return overrides();
}

std::vector<ShaderFile> read_shader_dir(const std::string& dir) {
  std::vector<ShaderFile> files;
  for (const std::string& name : shader_names()) {
    const std::filesystem::path p = std::filesystem::path(dir) / name;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(p, ec)) continue;
    std::ifstream in(p, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    if (!in && !in.eof()) throw std::runtime_error("shader file '" + p.string() + "': cannot be read");
    files.push_back({name, text.str()});
  }
  return files;
}

std::string shader_text(const std::string& name) {
  const char* t = find_embedded(name);
  if (t == nullptr) throw std::invalid_argument("unknown shader '" + name + "'");
  return t;
}

ExpandedShader expand_shader(const std::string& name, const std::string& defines) {
  return expand_shader(name, defines, {});
}

ExpandedShader expand_shader(const std::string& name, const std::string& defines,
                             const std::vector<ShaderFile>& extra_files) {
  return Expander(extra_files).run(name, defines);
}

std::string shader_display_path(const std::string& file) {
  return file == kDefinesName ? file : "shaders/" + file;
}

std::string map_shader_log(const std::string& log, const std::vector<std::string>& files) {
  // Mesa: "0:12(5): error: ..."; glslang/AMD: "ERROR: 0:12: ..."; NVIDIA: "0(12) : error C...".
  static const std::regex mesa_re(R"(^\s*(\d+):(\d+)\(\d+\):\s*(.*)$)");
  static const std::regex glslang_re(R"(^\s*(ERROR|WARNING):\s*(\d+):(\d+):\s*(.*)$)");
  static const std::regex nvidia_re(R"(^\s*(\d+)\((\d+)\)\s*:\s*(.*)$)");
  // "path:line" for a reported source string and line; a line >= kShaderLineBase names its file.
  const auto location = [&](const std::string& source, const std::string& line_text) -> std::string {
    unsigned long long k = std::stoull(source), line = std::stoull(line_text);
    if (line >= static_cast<unsigned long long>(kShaderLineBase)) {
      k = line / kShaderLineBase;
      line %= kShaderLineBase;
    }
    const std::string path = k < files.size() ? shader_display_path(files[k]) : "<source " + std::to_string(k) + ">";
    return path + ":" + std::to_string(line);
  };
  std::string out;
  for (const std::string& line : split_lines(log)) {
    std::smatch m;
    std::string mapped = line;
    if (std::regex_match(line, m, mesa_re) || std::regex_match(line, m, nvidia_re)) {
      mapped = location(m[1].str(), m[2].str()) + ": " + m[3].str();
    } else if (std::regex_match(line, m, glslang_re)) {
      std::string kind = m[1].str() == "ERROR" ? "error" : "warning";
      mapped = location(m[2].str(), m[3].str()) + ": " + kind + ": " + m[4].str();
    }
    if (!mapped.empty()) out += (out.empty() ? "" : "\n") + mapped;
  }
  return out;
}

}  // namespace nimbus::render
