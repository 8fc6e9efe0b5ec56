// The noisy sphere, camera, lights and optics of `nimbus bench clouds`, and its vdb_render runner
// (bench_clouds_scene.hpp).
#include "nimbus/app/bench_clouds_scene.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "nimbus/app/shell.hpp"
#include "nimbus/noise/noise.hpp"
#include "nimbus/render/image/image_io.hpp"

namespace nimbus::app {
namespace {

std::string vec3(const glm::dvec3& v) {
  std::ostringstream s;
  s.precision(17);
  s << v.x << "," << v.y << "," << v.z;
  return s.str();
}

}  // namespace

openvdb::FloatGrid::Ptr bench_noisy_sphere(int n) {
  openvdb::initialize();
  noise::NoiseParams p;
  p.kind = noise::Kind::Value;
  p.fractal = noise::Fractal::Fbm;
  p.octaves = 5;
  p.frequency = 4.0;  // 4 cells across the unit box, then 8, 16, 32, 64
  p.lacunarity = 2.0;
  p.gain = 0.5;
  p.seed = 7;
  const noise::NoiseField fbm(p);
  const double voxel = 1.0 / n;
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel));
  grid->transform().postTranslate(openvdb::Vec3d(0.5 * voxel));
  auto acc = grid->getAccessor();
  for (int k = -n / 2; k < n - n / 2; ++k)
    for (int j = -n / 2; j < n - n / 2; ++j)
      for (int i = -n / 2; i < n - n / 2; ++i) {
        const double x = (i + 0.5) * voxel, y = (j + 0.5) * voxel, z = (k + 0.5) * voxel;
        const double r = std::sqrt(x * x + y * y + z * z);
        double d = 0.0;
        if (r < 0.47) {
          const double f01 = 0.5 * (static_cast<double>(fbm.eval(x, y, z)) + 1.0);
          d = std::clamp(3.0 * (0.38 - r) / 0.38 + 2.5 * (f01 - 0.5), 0.0, 1.0);
        }
        acc.setValue(openvdb::Coord(i, j, k), static_cast<float>(d));
      }
  return grid;
}

render::Camera bench_camera(int width, int height) {
  render::Camera c;
  c.eye = {0.0, 0.0, 1.4};
  c.look_at = {0.0, 0.0, 0.0};
  c.up = {0.0, 1.0, 0.0};
  c.fov_deg = 360.0 / M_PI * std::atan(41.2136 / (2.0 * 50.0));  // openvdb PerspectiveCamera defaults
  c.width = width;
  c.height = height;
  c.near_m = 0.05;
  c.far_m = 10.0;
  return c;
}

render::Light bench_light(bool back_lit) {
  render::Light l;
  l.direction_to_sun = back_lit ? glm::dvec3(0.3, 0.5, -0.8) : glm::dvec3(0.6, 0.8, 0.3);
  l.irradiance_w_m2 = glm::dvec3(1.0);
  return l;
}

render::CloudOptics vdb_render_optics(const VdbRenderSettings& s, double voxel_m) {
  render::CloudOptics o;
  o.extinction_per_m = (s.absorb_per_voxel + s.scatter_per_voxel) / voxel_m;
  o.albedo = glm::dvec3(s.scatter_per_voxel / (s.absorb_per_voxel + s.scatter_per_voxel));
  o.ambient_radiance = glm::dvec3(0.0);
  return o;
}

render::CloudOptics bench_optics(double voxel_m) { return vdb_render_optics(VdbRenderSettings{}, voxel_m); }

VdbRenderRun run_vdb_render(const std::string& vdb_render, const std::filesystem::path& vdb,
                            const std::filesystem::path& exr, const render::Camera& camera,
                            const glm::dvec3& direction_to_sun, const VdbRenderSettings& s) {
  VdbRenderRun run;
  const auto rgb = [](double v) { return vec3(glm::dvec3(v)); };
  std::ostringstream cmd;
  cmd << shell_quote(vdb_render) << " " << shell_quote(vdb.string()) << " " << shell_quote(exr.string()) << " -res "
      << camera.width << "x" << camera.height << " -translate " << vec3(camera.eye) << " -lookat "
      << vec3(camera.look_at) << " -up " << vec3(camera.up) << " -fov " << camera.fov_deg << " -absorb "
      << rgb(s.absorb_per_voxel) << " -scatter " << rgb(s.scatter_per_voxel) << " -light "
      << vec3(glm::normalize(direction_to_sun)) << ",1,1,1 -gain 0 -step " << s.step << " -shadowstep "
      << s.shadow_step << " -v";
  if (s.cutoff > 0.0) cmd << " -cutoff " << s.cutoff;
  if (s.cpus > 0) cmd << " -cpus " << s.cpus;
  run.command = cmd.str();
  const auto t0 = std::chrono::steady_clock::now();
  const ShellResult done = run_shell(run.command);
  run.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (done.exit_code != 0)
    throw std::runtime_error("failed (exit " + std::to_string(done.exit_code) + ", signal " +
                             std::to_string(done.signal) + "): " + run.command + "\n" + done.output);
  const std::string& output = done.output;
  // "vdb_render: ray-tracing density..." is followed by "...completed in T sec".
  const std::regex timing("ray-tracing[^\\n]*\\n[^\\n]*completed in ([0-9.eE+-]+) sec");
  std::smatch m;
  if (std::regex_search(output, m, timing)) run.render_s = std::stod(m[1].str());
  run.image = render::read_exr(exr);
  return run;
}

}  // namespace nimbus::app
