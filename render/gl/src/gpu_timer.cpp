// GPU pass timing (gpu_timer.hpp).
#include "nimbus/render/gl/gpu_timer.hpp"

#include <cstring>

namespace nimbus::render {

GpuTimer::GpuTimer(int slots, bool enabled, Clock clock)
    : enabled_(enabled), ms_(static_cast<std::size_t>(slots > 0 ? slots : 0), 0.0), fragments_(ms_.size(), 0.0) {
  if (!enabled_) return;
  counts_ = epoxy_has_gl_extension("GL_ARB_pipeline_statistics_query");
  GLint bits = 0;
  glGetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &bits);
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  queries_ = clock == Clock::Auto && bits > 0 && !(renderer != nullptr && std::strstr(renderer, "llvmpipe") != nullptr);
  if (!queries_) glFinish();
}

void GpuTimer::finish() {
  for (const auto& [slot, query] : pending_) {
    GLuint64 ns = 0;
    glGetQueryObjectui64v(query.id(), GL_QUERY_RESULT, &ns);
    ms_.at(static_cast<std::size_t>(slot)) += static_cast<double>(ns) * 1e-6;
  }
  pending_.clear();
  for (const auto& [slot, query] : counting_) {
    GLuint64 n = 0;
    glGetQueryObjectui64v(query.id(), GL_QUERY_RESULT, &n);
    fragments_.at(static_cast<std::size_t>(slot)) += static_cast<double>(n);
  }
  counting_.clear();
}

double GpuTimer::total_ms() const {
  double sum = 0.0;
  for (double v : ms_) sum += v;
  return sum;
}

std::string GpuTimer::method() const {
  return !enabled_ ? "not timed" : queries_ ? "GL_TIME_ELAPSED query" : "glFinish + steady_clock";
}

GpuTiming gpu_time(const std::function<void()>& draw) {
  glFinish();  // earlier work is not ours to time
  GpuTimer timer(1);
  timer.time(0, draw);
  timer.finish();
  check_gl("gpu_time");
  return {timer.ms(0), timer.method()};
}

}  // namespace nimbus::render
