// The one GPU timer: GPU work measured pass by pass, summed per kind of pass. GL_TIME_ELAPSED
// queries where the driver's are trustworthy; else glFinish after each pass around
// std::chrono::steady_clock (llvmpipe's timer queries are unreliable across framebuffer changes).
// A disabled timer runs the work and waits for nothing, so frames nobody times cost nothing extra.
// Where the driver counts them (GL_ARB_pipeline_statistics_query), an enabled timer also counts
// each kind of pass's fragment shader invocations: what its time is read against (the device's
// rate per fragment, `nimbus bench gl`).
#pragma once
#include <epoxy/gl.h>

#include <chrono>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "nimbus/render/gl/resources.hpp"

namespace nimbus::render {

class GpuTimer {
 public:
  enum class Clock {
    Auto,  // queries where trustworthy (a GPU), else Wall (llvmpipe, or no timer bits)
    Wall,  // always glFinish + steady_clock: the same clock on every device
  };

  // `slots` kinds of pass, numbered 0 .. slots - 1. Enabled with the Wall clock, earlier GL work is
  // finished first so that it is not counted. Needs a current GL context.
  explicit GpuTimer(int slots, bool enabled = true, Clock clock = Clock::Auto);

  // Runs `f` and adds its time to `slot`. With the Wall clock a pass also counts any untimed GL
  // work issued since the previous pass ended.
  template <class F>
  void time(int slot, F&& f) {
    if (!enabled_) {
      f();
    } else if (queries_) {
      pending_.emplace_back(slot, make_query(GL_TIME_ELAPSED));
      glBeginQuery(GL_TIME_ELAPSED, pending_.back().second.id());
      counted(slot, f);
      glEndQuery(GL_TIME_ELAPSED);
    } else {
      const auto t0 = std::chrono::steady_clock::now();
      counted(slot, f);
      glFinish();
      ms_.at(static_cast<std::size_t>(slot)) +=
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    }
  }

  // Waits for the pending queries and adds them up; ms() and fragments() are final after it.
  void finish();
  double ms(int slot) const { return ms_.at(static_cast<std::size_t>(slot)); }
  // Fragment shader invocations of the slot's passes; -1 where the driver does not count them.
  double fragments(int slot) const { return counts_ ? fragments_.at(static_cast<std::size_t>(slot)) : -1.0; }
  double total_ms() const;
  bool enabled() const { return enabled_; }
  // "GL_TIME_ELAPSED query", "glFinish + steady_clock" or "not timed".
  std::string method() const;

 private:
  // Runs `f` inside a fragment count when the driver has one (ending the query if `f` throws:
  // a query left open would fail the next one).
  template <class F>
  void counted(int slot, F&& f) {
    if (counts_) {
      GLuint id = 0;  // glGenQueries: Mesa's glCreateQueries refuses the statistics targets
      glGenQueries(1, &id);
      counting_.emplace_back(slot, GlQuery(id));
      glBeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, counting_.back().second.id());
    }
    try {
      f();
    } catch (...) {
      if (counts_) glEndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
      if (queries_) glEndQuery(GL_TIME_ELAPSED);
      throw;
    }
    if (counts_) glEndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
  }

  bool enabled_ = false, queries_ = false, counts_ = false;
  std::vector<std::pair<int, GlQuery>> pending_, counting_;
  std::vector<double> ms_, fragments_;
};

// One piece of GPU work timed alone (earlier work finished first) with the Auto clock.
struct GpuTiming {
  double ms = 0.0;
  std::string method;  // GpuTimer::method()
};
GpuTiming gpu_time(const std::function<void()>& draw);

}  // namespace nimbus::render
