// `nimbus bench clouds` (bench_clouds.cpp): its flags, and what its sun rows and its lamp rows
// (bench_clouds_lamps.cpp) share to measure the slicer against the CPU reference
// (bench_clouds_measure.cpp): the covered-pixel error, best-of-N timing, the reference with progress.
#pragma once
#include <string>
#include <vector>

#include "nimbus/render/clouds/cloud_renderer.hpp"
#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/core/cloud_volume.hpp"
#include "nimbus/render/core/image.hpp"
#include "nimbus/render/image/image_metrics.hpp"

namespace nimbus::cli::bench_clouds {

constexpr double kPi = 3.14159265358979323846;
constexpr double kCovered = 0.01;  // a pixel counts where the reference's alpha exceeds this

struct BenchCloudsArgs {
  std::string res = "512x512";
  int volume_res = 128;
  std::string slices = "32,64,128,256,512";
  std::string light_res = "128,256,512,1024";
  std::string lights = "front,back";
  int repeat = 3;
  std::string ref_steps = "0.25,0.5";
  bool jitter = false;
  std::string format = "r16f";
  std::string vdb_render = "/usr/bin/vdb_render";
  bool no_vdb_render = false, no_switches = false, no_sweep = false, no_sun = false, no_lamps = false;
  std::string lamp_distances = "4,1.5,0.75";  // metres from the sphere's centre (its radius is 0.47)
  std::string lamp_slices = "64,128,256";
  double steam_voxel = 0.003;                 // the steam-under-a-lamp row's voxel, metres (0: skip the row)
  int switch_slices = 128, switch_light_res = 256;
  double sweep_half_deg = 10.0, sweep_step_deg = 0.5;
  std::string plot, out_dir, reference_dir;
};

// A comma-separated list of integers in [lo, hi]; a usage error naming the flag.
std::vector<int> int_list(const std::string& flag, const std::string& text, int lo, int hi);

// Error of `test` against `reference` over the covered pixels (reference alpha > kCovered):
// compare_images on the radiance with the uncovered pixels of the reference blacked out, and
// the RMSE of alpha.
struct CoveredError {
  render::ImageError radiance;
  double alpha_rmse = 0.0;
};
CoveredError covered_error(const render::Image& test, const render::Image& reference);

// vdb_render's radiance carries an unnormalised phase (weight 1): ours is it / 4 pi.
render::Image normalise_vdb(render::Image img);

// dir/name.exr (and a .png preview when asked); nothing without a directory.
void save(const std::string& dir, const std::string& name, const render::Image& img, bool preview);

// The best of `repeat` timed frames after a warm-up.
struct Timed {
  render::Image image;
  render::CloudFrameStats best;  // best GPU total of the repeats
  double best_wall_ms = 1e300;
};
Timed timed_render(render::CloudRenderer& r, const render::Camera& cam, const std::vector<render::Light>& lights,
                   const render::CloudSliceSettings& s, int repeat);
Timed timed_render(render::CloudRenderer& r, const render::Camera& cam, const render::Light& light,
                   const render::CloudSliceSettings& s, int repeat);

// The CPU single-scattering reference (double precision) at the given steps, with a progress line.
render::Image reference_with_progress(const std::vector<render::CloudVolume>& clouds, const render::Camera& cam,
                                      const std::vector<render::Light>& light, double view_step,
                                      double shadow_step, const std::string& what);

// A sun-lit case and its reference.
struct Lit {
  bool back;
  render::Light light;
  render::Image reference;
};

// The switch rows (bench_clouds_sweep.cpp): the optional terms one at a time against each sun-lit
// case's single-scattering reference.
void switch_rows(const BenchCloudsArgs& a, render::CloudRenderer& renderer, const render::Camera& camera,
                 const std::vector<Lit>& lits);
// The popping sweep (bench_clouds_sweep.cpp): the light through the slicer's branch switch.
void sweep_rows(const BenchCloudsArgs& a, render::CloudRenderer& renderer, const render::Camera& camera);

// --lamp-distances as metres; a usage error naming the flag.
std::vector<double> lamp_distances(const BenchCloudsArgs& a);

// The lamp rows (bench_clouds_lamps.cpp): the noisy sphere under a lamp near and far, two lamps at
// once, and the steam under the street lamp.
void bench_lamps(const BenchCloudsArgs& a, render::CloudRenderer& renderer, const std::vector<render::CloudVolume>& clouds,
                 const render::Camera& camera, const std::vector<bool>& back_lit, double ref_view, double ref_shadow);

}  // namespace nimbus::cli::bench_clouds
