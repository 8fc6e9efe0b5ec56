// The default sky's keyframes, as the viewer makes them and plainly (bench_volume_keyframes.hpp).
#include "bench_volume_keyframes.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>
#include <vector>

#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/sky.hpp"
#include "nimbus/volume/up_axis.hpp"

namespace nimbus::cli {
namespace {

using Grids = std::vector<openvdb::FloatGrid::Ptr>;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Every preset cloud of the sky at keyframe k, each y-up; `reuse` null: the plain way.
Grids make_keyframe(const volume::Sky& sky, int k, std::vector<volume::GenerationReuse>* reuse) {
  Grids grids;
  for (std::size_t i = 0; i < sky.clouds.size(); ++i) {
    if (sky.clouds[i].preset.empty()) continue;
    volume::GenerateOptions o;
    o.voxel_size = sky.voxel_size_m;
    o.time = double(k) * sky.keyframe_interval_s;
    if (reuse) {
      o.reuse = &(*reuse)[i];
      o.y_up = true;
      grids.push_back(volume::generate_density(volume::sky_cloud_params(sky, i), o));
    } else {
      grids.push_back(volume::rotate_z_up_to_y_up(*volume::generate_density(volume::sky_cloud_params(sky, i), o)));
    }
  }
  return grids;
}

bool same_voxels(const Grids& a, const Grids& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i]->activeVoxelCount() != b[i]->activeVoxelCount()) return false;
    auto acc = b[i]->getConstAccessor();
    for (auto it = a[i]->cbeginValueOn(); it; ++it) {
      float v = 0.0f;
      if (!acc.probeValue(it.getCoord(), v) || v != *it) return false;
    }
  }
  return true;
}

}  // namespace

void bench_sky_keyframes(int count) {
  const volume::Sky sky = volume::default_sky();
  std::printf("\n### Sky keyframes (the default sky: %zu clouds at %g m voxels, every %g s of sky time; %u threads)\n\n",
              sky.clouds.size(), sky.voxel_size_m, sky.keyframe_interval_s, std::thread::hardware_concurrency());
  std::printf("| keyframe | plain: tests made, turned y-up (anchor) s | as the viewer makes them: tests read, y-up s | ratio | voxels |\n");
  std::printf("|---:|---:|---:|---:|---|\n");
  std::vector<volume::GenerationReuse> reuse(sky.clouds.size());
  double plain_sum = 0.0, viewer_sum = 0.0;
  for (int k = 0; k < count; ++k) {
    auto t0 = std::chrono::steady_clock::now();
    const Grids plain = make_keyframe(sky, k, nullptr);
    const double plain_s = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    const Grids viewer = make_keyframe(sky, k, &reuse);
    const double viewer_s = seconds_since(t0);
    int64_t active = 0;
    for (const auto& g : viewer) active += int64_t(g->activeVoxelCount());
    std::printf("| %d%s | %.3f | %.3f | %.2f | %s (%lld active) |\n", k, k == 0 ? " (tests saved)" : "", plain_s, viewer_s,
                plain_s / viewer_s, same_voxels(plain, viewer) ? "identical" : "DIFFER", static_cast<long long>(active));
    std::fflush(stdout);
    if (k > 0) {
      plain_sum += plain_s;
      viewer_sum += viewer_s;
    }
  }
  if (count > 1)
    std::printf("| after the first | %.3f | %.3f | %.2f | |\n", plain_sum / (count - 1), viewer_sum / (count - 1),
                plain_sum / viewer_sum);
}

}  // namespace nimbus::cli
