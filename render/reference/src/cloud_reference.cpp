// The CPU reference of the cloud model (cloud_reference.hpp): single scattering of the sun plus
// the ambient sky term, midpoint steps in double precision, Hillaire 2015 step integral.
#include "nimbus/render/reference/cloud_reference.hpp"
#include "nimbus/render/scene/metadata.hpp"
#include "per_pixel.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>

namespace nimbus::render {
namespace {


bool finite3(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Edge length of the cloud's smallest voxel axis, metres.
double voxel_size_m(const CloudVolume& c) {
  double v = 1e300;
  for (int a = 0; a < 3; ++a) v = std::min(v, glm::length(glm::dvec3(c.index_to_world[a])));
  return v;
}

void validate_clouds(const std::vector<CloudVolume>& clouds) {
  if (clouds.empty()) throw std::invalid_argument("cloud reference clouds: the list is empty");
  for (const CloudVolume& c : clouds) {
    validate(c.optics);
    const std::size_t n = static_cast<std::size_t>(c.box.size[0]) * c.box.size[1] * c.box.size[2];
    if (c.box.size[0] <= 0 || c.box.size[1] <= 0 || c.box.size[2] <= 0 || c.box.values.size() != n)
      throw std::invalid_argument("cloud '" + c.name + "': box size does not match its values");
    const double v = voxel_size_m(c);
    if (!std::isfinite(v) || !(v > 0.0)) throw std::invalid_argument("cloud '" + c.name + "': voxel size must be > 0");
    if (!c.next_box.values.empty() && (c.next_box.origin != c.box.origin || c.next_box.size != c.box.size ||
                                       c.next_box.values.size() != n))
      throw std::invalid_argument("cloud '" + c.name + "': its next keyframe must lie on the same box");
    if (!(c.blend >= 0.0 && c.blend <= 1.0) || (c.blend > 0.0 && c.next_box.values.empty()))
      throw std::invalid_argument("cloud '" + c.name + "': keyframe blend must be in [0, 1], and 0 without a next keyframe");
    if (!finite3(c.world_min) || !finite3(c.world_max))
      throw std::invalid_argument("cloud '" + c.name + "': world bounds must be finite");
  }
}

// Ray parameter interval [t0, t1] (t0 >= 0) inside an axis-aligned box; false if missed.
bool clip_to_box(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& lo, const glm::dvec3& hi, double& t0,
                 double& t1) {
  t0 = 0.0;
  t1 = 1e300;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return false;
      continue;
    }
    double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 < t1;
}

// One cloud seen along one ray, in its own index space: the point at ray parameter t is
// origin + t * step (affine map, so a world ray stays a line), sampled with the same trilinear
// weights as sample_density (OpenVDB BoxSampler, 0 outside the active box).
struct IndexRay {
  const CloudVolume* cloud;
  glm::dvec3 origin, dir;  // box-local index coordinates (voxel centres at integers)
  double extinction_per_m;

  IndexRay(const CloudVolume& c, const glm::dvec3& o, const glm::dvec3& d) : cloud(&c) {
    const glm::dvec3 shift(c.box.origin[0], c.box.origin[1], c.box.origin[2]);
    origin = glm::dvec3(c.world_to_index * glm::dvec4(o, 1.0)) - shift;
    dir = glm::dvec3(c.world_to_index * glm::dvec4(d, 0.0));
    extinction_per_m = c.optics.extinction_per_m;
  }

  double density(double t) const { return sample_density_local(*cloud, origin + t * dir); }
};

// What every ray needs: the clouds, their union box, the finest voxel and the lights.
struct Prepared {
  const std::vector<CloudVolume>& clouds;
  const std::vector<Light>& lights;
  glm::dvec3 box_min, box_max;   // union of the supports
  double voxel_m = 1e300;        // finest voxel edge

  Prepared(const std::vector<CloudVolume>& c, const std::vector<Light>& l) : clouds(c), lights(l) {
    cloud_bounds(clouds, box_min, box_max);
    for (const CloudVolume& cloud : clouds) voxel_m = std::min(voxel_m, voxel_size_m(cloud));
  }

  // exp(-optical depth) from p along unit `to_light` up to `distance_m` (the light; infinite for
  // the sun), midpoint steps of at most step_m, clipped to the union box.
  double light_transmittance(const glm::dvec3& p, const glm::dvec3& to_light, double distance_m, double step_m) const {
    double t0 = 0.0, t1 = 0.0;
    if (!clip_to_box(p, to_light, box_min, box_max, t0, t1)) return 1.0;
    t1 = std::min(t1, distance_m);
    if (!(t1 > t0)) return 1.0;
    const double length = t1 - t0;
    const int n = std::max(1, static_cast<int>(std::ceil(length / step_m - 1e-9)));
    const double h = length / n;
    double tau = 0.0;
    for (const CloudVolume& c : clouds) {
      const IndexRay r(c, p, to_light);
      double rho_sum = 0.0;
      for (int k = 0; k < n; ++k) rho_sum += r.density(t0 + (k + 0.5) * h);
      tau += r.extinction_per_m * rho_sum * h;
    }
    return std::exp(-tau);
  }
};

CloudSample trace(const Prepared& P, const glm::dvec3& eye, const glm::dvec3& dir, const CloudReferenceSettings& s) {
  // The ray's intervals inside each cloud's support, merged into disjoint spans.
  std::vector<std::pair<double, double>> spans;
  for (const CloudVolume& c : P.clouds) {
    double t0 = 0.0, t1 = 0.0;
    if (clip_to_box(eye, dir, c.world_min, c.world_max, t0, t1)) spans.emplace_back(t0, t1);
  }
  std::sort(spans.begin(), spans.end());
  std::vector<std::pair<double, double>> merged;
  for (const auto& sp : spans) {
    if (!merged.empty() && sp.first <= merged.back().second) {
      merged.back().second = std::max(merged.back().second, sp.second);
    } else {
      merged.push_back(sp);
    }
  }
  std::vector<IndexRay> rays;
  rays.reserve(P.clouds.size());
  for (const CloudVolume& c : P.clouds) rays.emplace_back(c, eye, dir);
  const double view_step = s.view_step_voxels * P.voxel_m;
  const double shadow_step = s.shadow_step_voxels * P.voxel_m;
  std::vector<double> rho(P.clouds.size());

  glm::dvec3 radiance(0.0);
  double transmittance = 1.0;
  for (const auto& [t0, t1] : merged) {
    const int n = std::max(1, static_cast<int>(std::ceil((t1 - t0) / view_step - 1e-9)));
    const double h = (t1 - t0) / n;
    for (int k = 0; k < n && transmittance >= s.min_transmittance; ++k) {
      const double t = t0 + (k + 0.5) * h;
      double sigma_t = 0.0;
      glm::dvec3 ambient(0.0);  // sum_i sigma_s,i L_amb,i
      for (std::size_t i = 0; i < rays.size(); ++i) {
        rho[i] = rays[i].density(t);
        if (rho[i] == 0.0) continue;
        const double ext = rays[i].extinction_per_m * rho[i];
        sigma_t += ext;
        ambient += P.clouds[i].optics.albedo * ext * P.clouds[i].optics.ambient_radiance;
      }
      if (!(sigma_t > 0.0)) continue;
      const glm::dvec3 x = eye + t * dir;
      glm::dvec3 source = ambient;  // W sr^-1 m^-3
      for (const Light& light : P.lights) {
        const LightAtPoint a = light_at(light, x);
        if (!(glm::length(a.irradiance_w_m2) > 0.0)) continue;
        // Phase angle between the light's propagation (-to_light) and the way to the eye (-dir).
        const double cos_theta = glm::dot(a.to_light, dir);
        glm::dvec3 weight(0.0);  // sum_i sigma_s,i p_i
        for (std::size_t i = 0; i < rays.size(); ++i) {
          if (rho[i] == 0.0) continue;
          weight += P.clouds[i].optics.albedo * (rays[i].extinction_per_m * rho[i]) *
                    phase_value(P.clouds[i].optics.phase, cos_theta);
        }
        source += weight * a.irradiance_w_m2 * P.light_transmittance(x, a.to_light, a.distance_m, shadow_step);
      }
      const double step_t = std::exp(-sigma_t * h);
      // Hillaire 2015 step integral: the source is constant over the step, extinction is too.
      radiance += transmittance * (source / sigma_t) * (1.0 - step_t);
      transmittance *= step_t;
    }
  }
  return {radiance, 1.0 - transmittance};
}

void describe(Image& image, const std::vector<CloudVolume>& clouds, const Camera& c, const std::vector<Light>& lights,
              const CloudReferenceSettings& s) {
  std::ostringstream v, sh, mt;
  v << s.view_step_voxels;
  sh << s.shadow_step_voxels;
  mt << s.min_transmittance;
  image.metadata["method"] = "cloud-reference";
  image.metadata["view_step_voxels"] = v.str();
  image.metadata["shadow_step_voxels"] = sh.str();
  image.metadata["min_transmittance"] = mt.str();
  image.metadata["camera"] = describe_camera(c);
  image.metadata["light"] = describe_lights(lights);
  std::string names;
  for (const CloudVolume& cloud : clouds) names += (names.empty() ? "" : ", ") + cloud.name;
  image.metadata["clouds"] = names;
}

}  // namespace

void validate(const CloudReferenceSettings& s) {
  if (!std::isfinite(s.view_step_voxels) || !(s.view_step_voxels > 0.0) || !(s.view_step_voxels <= 8.0))
    throw std::invalid_argument("cloud reference view_step_voxels: must be in (0, 8], got " +
                                std::to_string(s.view_step_voxels));
  if (!std::isfinite(s.shadow_step_voxels) || !(s.shadow_step_voxels > 0.0) || !(s.shadow_step_voxels <= 8.0))
    throw std::invalid_argument("cloud reference shadow_step_voxels: must be in (0, 8], got " +
                                std::to_string(s.shadow_step_voxels));
  if (!std::isfinite(s.min_transmittance) || !(s.min_transmittance >= 0.0) || !(s.min_transmittance <= 0.1))
    throw std::invalid_argument("cloud reference min_transmittance: must be in [0, 0.1], got " +
                                std::to_string(s.min_transmittance));
  if (s.threads < 0) throw std::invalid_argument("cloud reference threads: must be >= 0 (0 = all cores)");
}

static void validate_lights(const std::vector<Light>& lights) {
  if (lights.empty()) throw std::invalid_argument("cloud reference lights: the list is empty");
  for (const Light& l : lights) validate(l);
}

CloudSample cloud_reference_ray(const std::vector<CloudVolume>& clouds, const std::vector<Light>& lights,
                                const glm::dvec3& eye, const glm::dvec3& dir, const CloudReferenceSettings& settings) {
  validate_clouds(clouds);
  validate_lights(lights);
  validate(settings);
  if (!finite3(eye)) throw std::invalid_argument("cloud reference eye: must be finite");
  if (!finite3(dir) || !(glm::length(dir) > 0.0))
    throw std::invalid_argument("cloud reference dir: must be finite and non-zero");
  const Prepared prepared(clouds, lights);
  return trace(prepared, eye, glm::normalize(dir), settings);
}

CloudSample cloud_reference_ray(const std::vector<CloudVolume>& clouds, const Light& light, const glm::dvec3& eye,
                                const glm::dvec3& dir, const CloudReferenceSettings& settings) {
  return cloud_reference_ray(clouds, std::vector<Light>{light}, eye, dir, settings);
}

double cloud_light_transmittance(const std::vector<CloudVolume>& clouds, const Light& light,
                                 const glm::dvec3& point_m, double shadow_step_voxels) {
  if (clouds.empty()) return 1.0;  // nothing casts a shadow
  validate_clouds(clouds);
  validate(light);
  if (!std::isfinite(shadow_step_voxels) || !(shadow_step_voxels > 0.0) || !(shadow_step_voxels <= 8.0))
    throw std::invalid_argument("cloud reference shadow_step_voxels: must be in (0, 8], got " +
                                std::to_string(shadow_step_voxels));
  if (!finite3(point_m)) throw std::invalid_argument("cloud reference point_m: must be finite");
  const std::vector<Light> lights{light};
  const Prepared prepared(clouds, lights);
  const LightAtPoint a = light_at(light, point_m);
  return prepared.light_transmittance(point_m, a.to_light, a.distance_m, shadow_step_voxels * prepared.voxel_m);
}

Image render_cloud_reference(const std::vector<CloudVolume>& clouds, const Camera& camera,
                             const std::vector<Light>& lights, const CloudReferenceSettings& settings) {
  validate_clouds(clouds);
  validate(camera);
  validate_lights(lights);
  validate(settings);
  const Prepared prepared(clouds, lights);
  Image image(camera.width, camera.height);
  describe(image, clouds, camera, lights, settings);
  detail::render_pixels(image, settings.threads, settings.progress, "cloud reference", [&](int x, int y) {
    const auto px = trace(prepared, camera.eye, pixel_ray(camera, x, y), settings);
    return glm::dvec4(px.radiance, px.alpha);
  });
  return image;
}

Image render_cloud_reference(const std::vector<CloudVolume>& clouds, const Camera& camera, const Light& light,
                             const CloudReferenceSettings& settings) {
  return render_cloud_reference(clouds, camera, std::vector<Light>{light}, settings);
}

}  // namespace nimbus::render
