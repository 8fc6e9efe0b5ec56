// `nimbus bench view`'s paths (bench_view_path.hpp).
#include "bench_view_path.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>

#include "nimbus/render/core/image_resample.hpp"
#include "nimbus/render/image/image_metrics.hpp"

namespace nimbus::cli {

using Clock = std::chrono::steady_clock;

// The passes of a frame whose GPU time bench view reports, in drawing order.
const char* const kPasses[8] = {"scene shadow maps", "scene surfaces", "shadow volume", "shafts", "cloud light",
                               "cloud slices", "composite", "GPU total"};

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double x = q * (v.size() - 1);
  const std::size_t i = static_cast<std::size_t>(x);
  return i + 1 < v.size() ? v[i] + (x - i) * (v[i + 1] - v[i]) : v.back();
}

namespace {

void add_pass_times(PathResult& r, const render::FrameStats& s) {
  const double t[] = {s.scene.shadow_maps_ms, s.scene.surfaces_ms, s.scene.shadow_volume_ms, s.scene.shafts_ms,
                      s.clouds.light_ms,      s.clouds.slices_ms,  s.clouds.composite_ms,    s.scene.total_ms + s.clouds.total_ms};
  const double n[] = {s.scene.shadow_maps_fragments, s.scene.surfaces_fragments, s.scene.shadow_volume_fragments,
                      s.scene.shafts_fragments,      s.clouds.light_fragments,  s.clouds.slices_fragments,
                      s.clouds.composite_fragments,  -1.0};
  for (std::size_t i = 0; i < std::size(kPasses); ++i) {
    r.pass_ms[kPasses[i]].push_back(t[i]);
    r.pass_fragments[kPasses[i]].push_back(n[i]);
  }
  if (r.timing.empty()) r.timing = s.clouds.timing.empty() ? s.scene.timing : s.clouds.timing;
}

}  // namespace

PathResult run_path(viewer::Viewer& v, Path path, int w, int h, int frames, bool adaptive, int error_every) {
  PathResult r;
  v.adaptive().enabled = adaptive;
  v.state().paused = path == Path::SunDrag;
  v.state().speed = path == Path::Orbit ? 10.0 : 30.0;
  double drag_end = -1.0;  // the clock at the current drag's last step; < 0: none pending
  bool first_seen = false;
  const auto k0 = v.keyframes().stats();
  const auto volume_stats = [&v] {
    return v.light_volumes() ? v.light_volumes()->stats() : render::KeyframeWorkerStats{};
  };
  const auto l0 = volume_stats();
  double clock = 0.0;          // real seconds the viewer has seen
  auto last = Clock::now();
  for (int f = 0; f < frames; ++f) {
    const auto now = Clock::now();
    const double dt = std::chrono::duration<double>(now - last).count();
    last = now;
    clock += dt;
    if (path == Path::Orbit) v.drag(0, 6.0, 0.0);  // 1.8 degrees a frame around the target
    if (path == Path::SunDrag && f % kDragCycle < kDragSteps) {
      v.set_sun(v.state().sky.sun_elevation_deg, std::fmod(v.state().sky.sun_azimuth_deg + kDragStepDeg, 360.0));
      if (f % kDragCycle == kDragSteps - 1) {
        drag_end = clock;
        first_seen = false;
      }
    }
    v.advance(dt);
    const bool busy = v.keyframes().stats().busy;
    const int64_t made = v.keyframes().stats().made;
    v.draw(w, h, clock);
    const viewer::FrameReport& rep = v.report();
    r.ms.push_back(rep.cpu_ms);
    if (rep.temporal_frames > 0) r.temporal_ms.push_back(rep.temporal_ms);
    add_pass_times(r, rep.stats);
    r.levels[rep.quality_level]++;
    r.held += rep.info.waited;
    r.stale += rep.info.multiple == "light volume (stale)";
    r.preview += rep.info.multiple == "light volume (preview)";
    if (path == Path::SunDrag && drag_end >= 0.0 && f % kDragCycle >= kDragSteps - 1) {
      // This frame's image is on screen when draw returns: the clock then.
      const double shown = clock + std::chrono::duration<double>(Clock::now() - now).count();
      if (!first_seen && (rep.info.multiple == "light volume (preview)" || rep.info.multiple == "light volume")) {
        r.sun_first_ms.push_back(1000.0 * (shown - drag_end));
        first_seen = true;
      }
      if (rep.info.multiple == "light volume") {
        r.sun_full_ms.push_back(1000.0 * (shown - drag_end));
        drag_end = -1.0;
      }
    }
    r.stand_in += v.state().slices.multiple.method == render::MultipleScatteringMethod::LightVolume && rep.info.multiple == "octaves";
    if (busy || v.keyframes().stats().made != made) r.longest_generating = std::max(r.longest_generating, rep.cpu_ms);
    // Not while the sun is dragged or its light awaited: the full-quality frame, drawn by the same
    // renderer, waits for the sun's full volumes, which would then be on screen sooner than the
    // viewer alone makes them.
    const bool awaiting_sun = path == Path::SunDrag && (f % kDragCycle < kDragSteps || drag_end >= 0.0);
    if (adaptive && error_every > 0 && f % error_every == 0 && !awaiting_sun) {
      // Outside the clock: the viewer does not see the time this takes.
      const render::Image full = v.full_quality_frame(w, h);
      r.errors.push_back(render::compare_images(render::upscale_bilinear(v.frame(), w, h), full).rel_rmse);
      last = Clock::now();
    }
  }
  const auto k1 = v.keyframes().stats();
  r.keyframes = k1.made - k0.made;
  r.keyframe_s = k1.seconds_total - k0.seconds_total;
  const auto l1 = volume_stats();
  r.volumes = l1.made - l0.made;
  r.volume_s = l1.seconds_total - l0.seconds_total;
  return r;
}

}  // namespace nimbus::cli
