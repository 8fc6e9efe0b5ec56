// The scene of `nimbus bench clouds` (docs/clouds.md, "Speed against error"): a value-noise fBm
// "noisy sphere" seen from (0, 0, 1.4) with vdb_render's default field of view and coefficients
// per voxel, front-lit and back-lit; and a runner for OpenVDB's vdb_render on it.
#pragma once
#include <openvdb/openvdb.h>

#include <filesystem>
#include <string>

#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/image.hpp"

namespace nimbus::app {

// vdb_render's coefficients, per voxel (its steps are in index space).
constexpr double kBenchAbsorbPerVoxel = 0.01;
constexpr double kBenchScatterPerVoxel = 0.1;

// n^3 voxels of edge 1/n centred on the origin (voxel (i, j, k) at ((i, j, k) + 0.5) / n for
// i in [-n/2, n/2)): density = clamp(3 (0.38 - r) / 0.38 + 2.5 (fbm - 0.5), 0, 1) for r < 0.47
// with fbm = nimbus value-noise fBm mapped to [0, 1] (5 octaves of 4 ... 64 cells across the box,
// gain 0.5, seed 7). Every voxel of the box is active (zeros included), so that vdb_render's
// intersector, which skips absent 8^3 leaves, sees the whole trilinear support.
openvdb::FloatGrid::Ptr bench_noisy_sphere(int n);

// Camera at (0, 0, 1.4) looking at the origin, up +y, vdb_render's default horizontal field of
// view (50 mm lens on a 41.2136 mm aperture: 44.775 degrees).
render::Camera bench_camera(int width, int height);

// Front-lit: the light behind the camera (0.6, 0.8, 0.3), dot(view, to_light) = -0.3.
// Back-lit: the light behind the cloud (0.3, 0.5, -0.8), dot(view, to_light) = +0.8.
// Irradiance 1 (vdb_render's light colour 1,1,1).
render::Light bench_light(bool back_lit);

// vdb_render_optics with the bench's coefficients.
render::CloudOptics bench_optics(double voxel_m);

// How OpenVDB's vdb_render (libopenvdb-tools) is run on a fog volume: its coefficients per voxel
// and its steps, all in index space.
struct VdbRenderSettings {
  double absorb_per_voxel = kBenchAbsorbPerVoxel;
  double scatter_per_voxel = kBenchScatterPerVoxel;
  double step = 1.0;         // -step (vdb_render's default 1)
  double shadow_step = 3.0;  // -shadowstep (its default 3)
  double cutoff = 0.0;       // -cutoff, the transmittance a ray stops at; 0: vdb_render's default
  int cpus = 0;              // -cpus; 0: all
};

// The optics that match vdb_render with `s` on voxels of `voxel_m`: isotropic, no ambient,
// extinction (absorb + scatter) / voxel per metre, albedo scatter / (absorb + scatter).
render::CloudOptics vdb_render_optics(const VdbRenderSettings& s, double voxel_m);

struct VdbRenderRun {
  render::Image image;      // as vdb_render wrote it (radiance with its unnormalised phase)
  double wall_s = 0.0;      // the whole process: read the VDB, render, write the EXR
  double render_s = 0.0;    // its own "ray-tracing ... completed in" time (-v), 0 if not printed
  std::string command;
};

// Runs vdb_render on `vdb` with `camera` (its horizontal field of view, eye, look-at and up), a
// light of colour 1 towards `direction_to_sun`, -gain 0 and `s`, writing `exr`, and reads the
// image back. Throws std::runtime_error naming the command when it fails.
VdbRenderRun run_vdb_render(const std::string& vdb_render, const std::filesystem::path& vdb,
                            const std::filesystem::path& exr, const render::Camera& camera,
                            const glm::dvec3& direction_to_sun, const VdbRenderSettings& s);

}  // namespace nimbus::app
