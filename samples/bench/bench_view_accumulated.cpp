// `nimbus bench view`'s accumulated-frame tables (bench_view_accumulated.hpp).
#include "bench_view_accumulated.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "nimbus/render/core/image_resample.hpp"
#include "nimbus/render/sky/progressive_frame.hpp"
#include "nimbus/render/sky/temporal_frame.hpp"
#include "nimbus/render/frame/sky_renderer.hpp"
#include "nimbus/render/image/image_metrics.hpp"
#include "viewer/camera_control.hpp"

namespace nimbus::cli {
namespace {

// The accumulated frames' levels (kTemporalQualityLevels) on the same still state: each level's
// frame alone, scaled up, and kAccumulated of its jittered frames accumulated
// (temporal_frame.hpp), against the full-quality frame and against the still view's mean of
// kConverged samples (that frame without its grain).
constexpr int kAccumulated = 8, kConverged = 16;

}  // namespace

void print_accumulated_levels(const render::ViewState& start, const viewer::ViewerOptions& options,
                              const std::vector<std::pair<int, int>>& sizes) {
  std::printf("\n## The accumulated frames' levels on the default view (time paused): one frame, and %d accumulated, "
              "against the full-quality frame and its still view's mean of %d samples\n\n", kAccumulated, kConverged);
  std::printf("| size | level | render scale | slices | vs full: one frame | vs full: %d accumulated | vs mean: one frame | "
              "vs mean: %d accumulated |\n", kAccumulated, kAccumulated);
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& [w, h] : sizes) {
    viewer::Viewer v(start, options);
    v.state().paused = true;
    v.draw(w, h, 0.0);
    const render::Image full = v.full_quality_frame(w, h);
    render::ProgressiveFrame mean;
    for (int i = 0; i < kConverged; ++i)
      mean.add(v.render_at(w, h, render::FrameQuality{1.0, 0, render::progressive_sample(static_cast<unsigned>(i))}), "still");
    for (int l = 0; l < viewer::kQualityLevelCount; ++l) {
      const viewer::QualityLevel& level = viewer::kTemporalQualityLevels[l];
      render::FrameQuality q = viewer::level_quality(level, start.slices.slices, start.slices.light_res);
      const render::Image one = render::upscale_bilinear(v.render_at(w, h, q), w, h);
      render::TemporalFrame accumulated;
      for (unsigned i = 1; i <= kAccumulated; ++i) {
        q.sample = {render::temporal_pixel_offset(i), i};
        const render::Image img = v.render_at(w, h, q);
        // A still camera: the history stays where it is, whatever the depths.
        render::Camera camera = render::state_camera(v.state(), img.width, img.height, {});
        camera.pixel_offset = q.sample.pixel_offset;
        accumulated.add(img, camera, render::PixelDepths{}, w, h);
      }
      std::printf("| %dx%d | %d | %.2f | %d | %.4f | %.4f | %.4f | %.4f |\n", w, h, l, q.render_scale, q.slices,
                  render::compare_images(one, full).rel_rmse, render::compare_images(accumulated.output(), full).rel_rmse,
                  render::compare_images(one, mean.mean()).rel_rmse,
                  render::compare_images(accumulated.output(), mean.mean()).rel_rmse);
    }
  }
}


void print_accumulated_motion(const render::ViewState& start, const std::vector<std::pair<int, int>>& sizes) {
  const viewer::QualityLevel& level = viewer::kTemporalQualityLevels[viewer::kQualityLevelCount - 1];
  constexpr int kFrames = 16;
  std::printf("\n## Accumulating while the camera turns (time paused; %d frames at %.2f of the pixels and %.2f of the "
              "slices, %.2f of the light buffer's side), against the last pose's still-view mean of %d samples\n\n",
              kFrames, level.render_scale, level.slice_share, level.light_share, kConverged);
  std::printf("| size | degrees a frame | accumulated | the last frame alone |\n|---|---:|---:|---:|\n");
  for (const auto& [w, h] : sizes)
    for (const double deg : {0.0, 1.0, 1.8}) {
      render::ViewState s = start;
      s.paused = true;
      render::SkyRenderer sky(s);
      render::TemporalFrame accumulated;
      render::Image small;
      for (unsigned i = 1; i <= kFrames; ++i) {
        if (i > 1) {  // the orbit path's move: a left drag, 0.3 degrees of tumble per pixel
          const viewer::CameraPose p = viewer::tumble({s.camera.eye, s.camera.look_at}, deg / 0.3, 0.0);
          s.camera.eye = p.eye;
        }
        render::FrameQuality q = viewer::level_quality(level, start.slices.slices, start.slices.light_res);
        q.sample = {render::temporal_pixel_offset(i), i};
        render::PixelDepths depths;
        render::SkyFrameInfo info;
        small = sky.render(s, w, h, q, true, nullptr, &info, &depths);
        accumulated.add(small, info.camera, depths, w, h);
      }
      render::ProgressiveFrame mean;
      for (int i = 0; i < kConverged; ++i)
        mean.add(sky.render(s, w, h, render::FrameQuality{1.0, 0, render::progressive_sample(static_cast<unsigned>(i))}, true),
                 "still");
      std::printf("| %dx%d | %.1f | %.4f | %.4f |\n", w, h, deg,
                  render::compare_images(accumulated.output(), mean.mean()).rel_rmse,
                  render::compare_images(render::upscale_bilinear(small, w, h), mean.mean()).rel_rmse);
      std::fflush(stdout);
    }
}

}  // namespace nimbus::cli
