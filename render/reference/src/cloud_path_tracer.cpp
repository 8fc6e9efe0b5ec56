// The cloud path tracer (cloud_path_tracer.hpp).
#include "nimbus/render/reference/cloud_path_tracer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "per_pixel.hpp"
#include "traced_media.hpp"
#include "nimbus/base/cancel.hpp"

namespace nimbus::render {

using namespace traced;

void validate(const PathTracerSettings& s) {
  if (s.samples_per_pixel < 1 || s.samples_per_pixel > (1 << 20))
    throw std::invalid_argument("path tracer samples_per_pixel: must be in [1, 1048576], got " + std::to_string(s.samples_per_pixel));
  if (s.max_bounces < 1 || s.max_bounces > 100000)
    throw std::invalid_argument("path tracer max_bounces: must be in [1, 100000], got " + std::to_string(s.max_bounces));
  if (s.roulette_after < 1) throw std::invalid_argument("path tracer roulette_after: must be >= 1");
  if (s.threads < 0) throw std::invalid_argument("path tracer threads: must be >= 0 (0 = all cores)");
  if (s.sky) {
    Scene probe;
    probe.sky = s.sky;
    probe.sun = Light{};
    validate(probe);
  }
}

struct PhotonTracer::Impl {
  std::vector<TracedCloud> media;
};

PhotonTracer::PhotonTracer(const std::vector<CloudVolume>& clouds) : impl_(std::make_unique<Impl>()) {
  impl_->media = media_of(clouds);
}

PhotonTracer::~PhotonTracer() = default;

PhotonExit PhotonTracer::trace(const glm::dvec3& origin, const glm::dvec3& dir, uint64_t seed, uint64_t stream,
                               int max_bounces, int roulette_after) const {
  const std::vector<TracedCloud>& media = impl_->media;
  PathRng rng(seed, stream);
  PhotonExit out;
  glm::dvec3 o = origin, d = glm::normalize(dir);
  for (int bounce = 0;; ++bounce) {
    const Collision c = collide(media, o, d, rng);
    if (c.medium < 0) {
      out.escaped = true;
      out.position = o;
      out.direction = d;
      out.bounces = bounce;
      return out;
    }
    if (bounce >= max_bounces) {
      out.bounces = bounce;
      return out;
    }
    const CloudVolume& cloud = *media[static_cast<std::size_t>(c.medium)].cloud;
    o += c.t * d;
    out.weight *= cloud.optics.albedo;
    if (bounce + 1 >= roulette_after) {
      if (!survives_roulette(out.weight, rng)) {
        out.bounces = bounce + 1;
        out.weight = glm::dvec3(0.0);
        return out;
      }
    }
    d = sample_phase(cloud.optics.phase, d, rng);
  }
}

PathTracedImage render_cloud_path_traced(const std::vector<CloudVolume>& clouds, const Camera& camera,
                                         const Light& light, const PathTracerSettings& settings) {
  validate(camera);
  validate(light);
  if (light.kind != LightKind::Sun)
    throw std::invalid_argument("cloud path tracer light: it traces the sun only; a lamp lights clouds through the slicer and the cloud reference");
  validate(settings);
  if (clouds.empty()) throw std::invalid_argument("path tracer clouds: the list is empty");
  const std::stop_token stop = current_stop_token();  // this call's, taken before the pixels fan out
  const std::vector<TracedCloud> media = media_of(clouds);
  const auto start = std::chrono::steady_clock::now();
  const glm::dvec3 to_light = glm::normalize(light.direction_to_sun);
  const int w = camera.width, h = camera.height, n = settings.samples_per_pixel;
  PathTracedImage out;
  out.image = Image(w, h);
  out.std_error.assign(static_cast<std::size_t>(w) * h * 3, 0.0f);

  detail::render_pixels(out.image, settings.threads, settings.progress, "cloud path tracer", [&](int x, int y) {
    const uint64_t pixel = static_cast<uint64_t>(y) * static_cast<uint64_t>(w) + static_cast<uint64_t>(x);
    PathRng rng(settings.seed, pixel);
    const glm::dvec3 ray = pixel_ray(camera, x, y);
    glm::dvec3 sum(0.0), sum_sq(0.0);
    double view_T = 0.0;
    for (int s = 0; s < n; ++s) {
      if ((s & 63) == 63) throw_if_stopped(stop);  // a stop (cancel.hpp) between 64 paths, not only between rows
      view_T += transmittance(media, camera.eye, ray, rng);
      glm::dvec3 L(0.0), beta(1.0);
      glm::dvec3 o = camera.eye, d = ray;
      for (int bounce = 0; bounce < settings.max_bounces; ++bounce) {
        const Collision c = collide(media, o, d, rng);
        if (c.medium < 0) {
          if (settings.sky && (bounce > 0 || settings.sky_background)) L += beta * sky_radiance(*settings.sky, d);
          break;
        }
        const CloudVolume& cloud = *media[static_cast<std::size_t>(c.medium)].cloud;
        o += c.t * d;
        beta *= cloud.optics.albedo;  // sigma_s / sigma_t at a real collision
        // Next-event estimation toward the sun: light propagating along -to_light scatters into -d.
        const double T_sun = transmittance(media, o, to_light, rng);
        if (T_sun > 0.0) L += beta * light.irradiance_w_m2 * (phase_value(cloud.optics.phase, glm::dot(to_light, d)) * T_sun);
        if (bounce + 1 >= settings.roulette_after) {
          if (!survives_roulette(beta, rng)) break;
        }
        d = sample_phase(cloud.optics.phase, d, rng);
      }
      sum += L;
      sum_sq += L * L;
    }
    const glm::dvec3 mean = sum / static_cast<double>(n);
    const glm::dvec3 var = glm::max(sum_sq / static_cast<double>(n) - mean * mean, glm::dvec3(0.0));
    float* se = out.std_error.data() + 3 * pixel;
    for (int c = 0; c < 3; ++c) se[c] = static_cast<float>(n > 1 ? std::sqrt(var[c] / (n - 1)) : 0.0);
    return glm::dvec4(mean, 1.0 - view_T / n);
  });
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Noise: the mean relative standard error of the luminance over covered pixels.
  double rel = 0.0;
  std::size_t covered = 0;
  for (std::size_t p = 0; p < static_cast<std::size_t>(w) * h; ++p) {
    const float* px = out.image.rgba.data() + 4 * p;
    const double lum = 0.2126 * px[0] + 0.7152 * px[1] + 0.0722 * px[2];
    if (px[3] <= 0.01f || !(lum > 0.0)) continue;
    const float* se = out.std_error.data() + 3 * p;
    rel += (0.2126 * se[0] + 0.7152 * se[1] + 0.0722 * se[2]) / lum;
    ++covered;
  }
  out.mean_relative_error = covered ? rel / covered : 0.0;
  std::ostringstream meta;
  meta << settings.samples_per_pixel << " samples per pixel, at most " << settings.max_bounces << " bounces, roulette after "
       << settings.roulette_after << ", seed " << settings.seed << ", mean relative standard error " << out.mean_relative_error;
  out.image.metadata["method"] = "cloud-path-tracer";
  out.image.metadata["path_tracer"] = meta.str();
  return out;
}

}  // namespace nimbus::render
