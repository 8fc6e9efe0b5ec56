// The airlight evaluations of airlight.hpp run through the shaders' own GLSL functions on an
// OpenGL 4.5 context (shaders/airlight_eval.comp.glsl), so the GPU path's error is measured
// against the same double-precision reference as the CPU one.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "nimbus/render/media/airlight.hpp"
#include "nimbus/render/gl/resources.hpp"
#include "nimbus/render/gl/shader_program.hpp"

namespace nimbus::render {

// The compute pass of airlight_eval.comp.glsl on the current GL context, for one method and
// phase: the queries are uploaded once and evaluated as often as asked, and the program is
// compiled in a step of its own, so that a benchmark can time the compile and the dispatches
// apart. std::invalid_argument for quadrature (CPU only), a table with a phase other than
// isotropic, or an invalid query.
class AirlightGlEvaluator {
 public:
  // Uploads the queries (and the method's F table); compiles nothing yet.
  AirlightGlEvaluator(const std::vector<AirlightQuery>& queries, const AirlightMethod& method, const Phase& phase);
  // Compiles the program with `defines` prepended (a unique #define makes the driver's shader
  // cache miss, so that the compile is timed cold). evaluate() compiles without defines if needed.
  void compile(const std::string& defines = "");
  // Evaluates the first `count` queries (all when count < 0 or past the end) and waits for them.
  void evaluate(int count = -1);
  // La of the first `count` queries, as the last evaluate() left them.
  std::vector<double> results(int count = -1) const;
  int size() const { return count_; }

 private:
  AirlightMethod method_;
  Phase phase_;
  int count_ = 0;
  std::optional<ShaderProgram> program_;
  GlBuffer in_, out_;
  GlTexture table_;
};

// evaluate_airlight through the GLSL functions: a headless context is created for the call. Quadrature has no GL form (std::invalid_argument);
// throws GlUnavailable when no context can be made.
std::vector<double> evaluate_airlight_gl(const std::vector<AirlightQuery>& queries, const AirlightMethod& method,
                                         const Phase& phase = {});

}  // namespace nimbus::render
