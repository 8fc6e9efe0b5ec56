// Airlight on an OpenGL context: shaders/airlight_eval.comp.glsl runs the shaders' own GLSL
// functions (stable, table:N with FTable::data() as an R32F texture, raymarch:N) on each query.
#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "nimbus/render/shafts/airlight_gl.hpp"
#include "nimbus/render/core/shader_contract.hpp"
#include "nimbus/render/gl/context.hpp"
#include "nimbus/render/gl/resources.hpp"
#include "nimbus/render/gl/shader_program.hpp"

namespace nimbus::render {

namespace {

struct GpuQuery {  // std430 layout of `Query` in airlight_eval.comp.glsl
  float beta, I0, Dsv, Dvp, cos_gamma, sin_gamma, march_length, unused;
};
static_assert(sizeof(GpuQuery) == 32);

constexpr int kGroupSize = 64;         // local_size_x
constexpr int kMaxGroupsPerCall = 16384;

}  // namespace

AirlightGlEvaluator::AirlightGlEvaluator(const std::vector<AirlightQuery>& queries, const AirlightMethod& method,
                                         const Phase& phase)
    : method_(method), phase_(phase) {
  if (method.kind == AirlightMethod::Quadrature)
    throw std::invalid_argument("airlight method 'quadrature' is CPU only (double precision); use --device cpu");
  if (method.kind == AirlightMethod::Table && phase.kind != PhaseKind::Isotropic)
    throw std::invalid_argument("airlight method '" + to_string(method) + "' is isotropic only (Sun's F(u, v))");
  std::vector<GpuQuery> input;
  input.reserve(queries.size());
  for (const AirlightQuery& q : queries) {
    validate(q);
    // cos and sin of gamma in double, then rounded, as airlight_stable does on the CPU.
    input.push_back({float(q.beta), float(q.I0), float(q.Dsv), float(q.Dvp), float(std::cos(q.gamma)),
                     float(std::sin(q.gamma)),
                     method.kind == AirlightMethod::RayMarch ? float(airlight_raymarch_length(q)) : 0.0f, 0.0f});
  }
  count_ = static_cast<int>(input.size());
  if (count_ == 0) return;
  in_ = make_buffer(static_cast<GLsizeiptr>(input.size() * sizeof(GpuQuery)), input.data(), 0);
  out_ = make_buffer(static_cast<GLsizeiptr>(input.size() * sizeof(float)), nullptr, 0);
  if (method.kind == AirlightMethod::Table) {
    const FTable table(method.n);
    TextureParams params;
    params.min_filter = params.mag_filter = GL_NEAREST;  // the shader interpolates itself
    table_ = make_texture_2d(GL_R32F, method.n, method.n, params);
    glTextureSubImage2D(table_.id(), 0, 0, 0, method.n, method.n, GL_RED, GL_FLOAT, table.data());
  }
}

void AirlightGlEvaluator::compile(const std::string& defines) {
  program_.emplace(std::vector<std::string>{"airlight_eval.comp.glsl"}, defines);
  program_->use();
  program_->set("u_method", airlight_eval_code(method_.kind));
  program_->set("u_n", method_.n);
  program_->set("u_phase_kind", phase_code(phase_.kind));
  program_->set("u_phase_g", float(phase_.g));
}

void AirlightGlEvaluator::evaluate(int count) {
  if (count < 0 || count > count_) count = count_;
  if (count == 0) return;
  if (!program_) compile();
  program_->use();
  program_->set("u_count", count);
  if (table_.id() != 0) glBindTextureUnit(contract::UNIT_F_TABLE, table_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, contract::STORAGE_AIRLIGHT_QUERIES, in_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, contract::STORAGE_AIRLIGHT_RESULTS, out_.id());
  const int per_call = kGroupSize * kMaxGroupsPerCall;
  for (int offset = 0; offset < count; offset += per_call) {
    const int n = std::min(per_call, count - offset);
    program_->set("u_offset", offset);
    glDispatchCompute(static_cast<GLuint>((n + kGroupSize - 1) / kGroupSize), 1, 1);
  }
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glFinish();
  check_gl("airlight evaluation (airlight_eval.comp.glsl)");
}

std::vector<double> AirlightGlEvaluator::results(int count) const {
  if (count < 0 || count > count_) count = count_;
  std::vector<float> result(static_cast<std::size_t>(count));
  if (count > 0)
    glGetNamedBufferSubData(out_.id(), 0, static_cast<GLsizeiptr>(result.size() * sizeof(float)), result.data());
  check_gl("airlight results (airlight_eval.comp.glsl)");
  return std::vector<double>(result.begin(), result.end());
}

std::vector<double> evaluate_airlight_gl(const std::vector<AirlightQuery>& queries, const AirlightMethod& method,
                                         const Phase& phase) {
  if (method.kind == AirlightMethod::Quadrature)
    throw std::invalid_argument("airlight method 'quadrature' is CPU only (double precision); use --device cpu");
  if (method.kind == AirlightMethod::Table && phase.kind != PhaseKind::Isotropic)
    throw std::invalid_argument("airlight method '" + to_string(method) + "' is isotropic only (Sun's F(u, v))");
  for (const AirlightQuery& q : queries) validate(q);
  if (queries.empty()) return {};
  auto context = GlContext::create_headless();  // destroyed last
  AirlightGlEvaluator evaluator(queries, method, phase);
  evaluator.evaluate();
  return evaluator.results();
}

}  // namespace nimbus::render
