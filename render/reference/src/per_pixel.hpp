// Shared by the CPU references: every pixel of a camera image from a function of (x, y), rows
// in parallel (TBB), with progress and a refusal of non-finite values.
#pragma once
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>

#include <glm/glm.hpp>

#include "nimbus/render/core/image.hpp"
#include "nimbus/base/cancel.hpp"

namespace nimbus::render::detail {

// Fills `image` (already sized) with pixel(x, y) = (R, G, B, A). `threads` 0 = all cores;
// progress (may be empty) gets the fraction of rows done, growing. A value that is not finite
// as a float throws std::runtime_error "<what>: pixel (x, y) is not finite".
inline void render_pixels(Image& image, int threads, const std::function<void(double)>& progress,
                          const std::string& what, const std::function<glm::dvec4(int, int)>& pixel) {
  int rows_done = 0;
  const std::stop_token stop = current_stop_token();  // this call's, taken before the rows fan out
  std::mutex progress_mutex;
  const auto render_rows = [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      throw_if_stopped(stop);  // a row at a time (cancel.hpp)
      for (int x = 0; x < image.width; ++x) {
        const glm::dvec4 v = pixel(x, y);
        float* out = image.pixel(x, y);
        for (int c = 0; c < 4; ++c) {
          const float f = static_cast<float>(v[c]);
          if (!std::isfinite(f))
            throw std::runtime_error(what + ": pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                     ") is not finite");
          out[c] = f;
        }
      }
      if (progress) {  // under the lock, so the reported fractions only grow
        const std::lock_guard<std::mutex> lock(progress_mutex);
        progress(static_cast<double>(++rows_done) / image.height);
      }
    }
  };
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] { tbb::parallel_for(tbb::blocked_range<int>(0, image.height, 1), render_rows); });
}

}  // namespace nimbus::render::detail
