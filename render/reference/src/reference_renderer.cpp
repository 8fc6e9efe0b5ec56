// The exact CPU reference: per pixel-centre ray, in double precision,
//   L = L_surface(P) e^(-sigma_t t_P) + sum over lights of the airlight over [0, t_P]
// (thesis eq. 23 without emission; t_P = inf for rays that escape), with the surface lit by
// Lambert's law (thesis eq. 24) and the airlight of a point light
//   int sigma_s p(theta) I0 w e^(-sigma_t d(x)) / d(x)^2 e^(-sigma_t x) V(x) dx
// (w a spot's cone weight, 1 for a lamp that shines every way)
// (thesis eq. 25 / Sun et al. eq. 5 with visibility V), of the sun
//   int sigma_s p(theta) E e^(-sigma_t x) V(x) dx  (closed form on each lit interval),
// and, with settings.surface_airlight, the airlight each surface reflects from each point
// light (Sun eq. 13's L_p,a, no occlusion; core/surface_airlight.hpp).
#include "nimbus/render/reference/reference_renderer.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "nimbus/render/scene/intersect.hpp"
#include "nimbus/render/core/quadrature.hpp"
#include "nimbus/render/media/spot_airlight.hpp"
#include "nimbus/render/media/surface_airlight.hpp"
#include "nimbus/render/reference/reference_visibility.hpp"
#include "nimbus/render/scene/metadata.hpp"
#include "per_pixel.hpp"

namespace nimbus::render {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Escaping rays are integrated to where the view-ray transmittance is e^-35 (6e-16) beyond
// the light; the rest is far below the quadrature tolerance.
constexpr double kTailOpticalDepth = 35.0;

// The scene prepared for rendering: intersection, and each point light's shadow regions of
// each occluder (reference_visibility.hpp).
struct Prepared {
  Prepared(const Scene& scene, bool with_surface_airlight) : tracer(scene) {
    if (with_surface_airlight && !scene.lamps.empty()) surface_airlight.emplace(scene.medium.phase);
    for (const Light& l : scene.lamps) {
      std::vector<ShadowRegion>& r = regions.emplace_back();
      for (std::size_t k = 0; k < tracer.occluder_count(); ++k) {
        glm::dvec3 lo, hi;
        tracer.occluder_bounds(k, lo, hi);
        r.push_back(point_shadow_region(l.position_m, lo, hi));
      }
    }
  }
  SceneTracer tracer;
  std::vector<std::vector<ShadowRegion>> regions;  // [light][occluder]
  std::optional<SurfaceAirlightTable> surface_airlight;  // when surfaces reflect the airlight
};

struct RayContext {
  const Prepared& prepared;
  const SceneTracer& tracer;
  const ReferenceSettings& settings;
  glm::dvec3 o, d;   // eye, unit direction
  double t_end;      // surface or bulb distance, or +inf
};

// Airlight of one point light per unit intensity (multiply by I0).
double point_airlight(const RayContext& ray, std::size_t index) {
  const Light& light = ray.tracer.scene().lamps[index];
  const Medium& m = ray.tracer.scene().medium;
  const double sigma_t = m.extinction_per_m, sigma_s = m.scattering_per_m();
  const glm::dvec3 v = light.position_m - ray.o;
  const double xc = glm::dot(v, ray.d);                  // closest approach along the ray
  const double h = glm::length(glm::cross(v, ray.d));    // its distance from the light
  const double x_end = std::isfinite(ray.t_end) ? ray.t_end : std::max(0.0, xc) + kTailOpticalDepth / sigma_t;

  const Intervals lit = point_light_lit_intervals(ray.tracer, ray.prepared.regions[index], light.position_m,
                                                  ray.o, ray.d, x_end, ray.settings.visibility_samples);
  if (lit.empty()) return 0.0;

  // Resolve the peak at the closest approach: cut at xc and at xc +- h 4^k, so that each piece
  // sees the 1 / (h^2 + (x - xc)^2) profile vary smoothly.
  std::vector<double> cuts{xc};
  if (h > 0.0) {
    for (double w = 0.25 * h; w < 4.0 * (x_end + std::abs(xc)); w *= 4.0) {
      cuts.push_back(xc - w);
      cuts.push_back(xc + w);
    }
  }
  for (double x : spot_cone_crossings(light, ray.o, ray.d)) cuts.push_back(x);  // a spot's cone edges
  std::sort(cuts.begin(), cuts.end());
  Intervals pieces;
  for (const auto& [a, b] : lit) {
    double start = a;
    for (const double c : cuts) {
      if (c > start && c < b) {
        pieces.emplace_back(start, c);
        start = c;
      }
    }
    pieces.emplace_back(start, b);
  }
  const Phase phase = m.phase;
  const bool spot = is_spot(light);
  const auto integrand = [&](double x) {
    const double dist = std::hypot(h, x - xc);
    const double cos_theta = (xc - x) / dist;  // light's travel direction vs. toward the eye
    const double w = spot ? spot_weight(light, (ray.o + x * ray.d - light.position_m) / dist) : 1.0;
    return sigma_s * phase_value(phase, cos_theta) * w * std::exp(-sigma_t * (x + dist)) / (dist * dist);
  };
  return integrate_adaptive(integrand, pieces, ray.settings.rel_tol).value;
}

// Airlight of the sun per unit irradiance (multiply by E): closed form per lit interval.
double sun_airlight(const RayContext& ray, const Light& sun) {
  const Medium& m = ray.tracer.scene().medium;
  const double sigma_t = m.extinction_per_m, sigma_s = m.scattering_per_m();
  const glm::dvec3 u = glm::normalize(sun.direction_to_sun);
  const bool escapes = !std::isfinite(ray.t_end);
  const double x_end = escapes ? kTailOpticalDepth / sigma_t : ray.t_end;
  const Intervals lit = sun_lit_intervals(ray.tracer, u, ray.o, ray.d, x_end, ray.settings.visibility_samples);
  // Light travels along -u, scatters toward the eye along -d: cos(theta) = u . d.
  const double p = phase_value(m.phase, glm::dot(u, ray.d));
  double sum = 0.0;
  for (const auto& [a, b] : lit) {
    // int_a^b e^(-sigma_t x) dx = e^(-sigma_t a) (1 - e^(-sigma_t (b - a))) / sigma_t
    const double span = (escapes && b == x_end) ? kInf : b - a;
    sum += std::exp(-sigma_t * a) * -std::expm1(-sigma_t * span) / sigma_t;
  }
  return sigma_s * p * sum;
}

// Lambert surface radiance at P (thesis eq. 24): albedo / pi * sum of the irradiances, plus the
// airlight reflected from each point light (Sun eq. 13), for every light whichever way the
// surface faces and unshadowed (Sun's model: no occlusion). A spot lights P by its cone's
// weight towards it and reflects no airlight (left out, as the shaders do: docs/shafts.md).
glm::dvec3 surface_radiance(const Prepared& prepared, const glm::dvec3& P, glm::dvec3 n,
                            const glm::dvec3& view_dir, const glm::dvec3& albedo) {
  const SceneTracer& tracer = prepared.tracer;
  const Scene& s = tracer.scene();
  if (glm::dot(n, view_dir) > 0.0) n = -n;  // the side the eye sees
  const double scale = 1.0 + std::max({std::abs(P.x), std::abs(P.y), std::abs(P.z)});
  const glm::dvec3 start = P + (1e-8 * scale) * n;  // off the surface for shadow rays
  glm::dvec3 irradiance{0.0};
  glm::dvec3 airlight{0.0};
  for (const Light& l : s.lamps) {
    const glm::dvec3 to_light = l.position_m - P;
    const double dist = glm::length(to_light);
    const double cos_i = glm::dot(n, to_light) / dist;
    const glm::dvec3 I = l.intensity_w_sr * (dist > 0.0 ? spot_weight(l, -to_light / dist) : 1.0);  // a spot's cone
    if (prepared.surface_airlight && dist > 0.0 && !is_spot(l)) {
      SurfaceAirlightQuery q;
      q.sigma_t = s.medium.extinction_per_m;
      q.sigma_s = s.medium.scattering_per_m();
      q.Dsp = dist;
      q.cos_theta_s = std::clamp(cos_i, -1.0, 1.0);
      airlight += l.intensity_w_sr * surface_airlight_table(q, *prepared.surface_airlight);
    }
    if (cos_i <= 0.0 || tracer.occluded(start, l.position_m)) continue;
    irradiance += I * (cos_i * std::exp(-s.medium.extinction_per_m * dist) / (dist * dist));
  }
  if (s.sun) {
    const glm::dvec3 u = glm::normalize(s.sun->direction_to_sun);
    const double cos_i = glm::dot(n, u);
    if (cos_i > 0.0 && !tracer.occluded_toward(start, u)) irradiance += s.sun->irradiance_w_m2 * cos_i;
  }
  if (s.sky) irradiance += sky_irradiance(*s.sky, n);
  return albedo / M_PI * irradiance + albedo * airlight;
}

// pixel_angle_rad: the angle one pixel subtends (the ground texture's footprint; 0 for a lone ray).
ReferenceSample trace(const Prepared& prepared, const glm::dvec3& eye, const glm::dvec3& dir,
                      const ReferenceSettings& settings, double pixel_angle_rad) {
  const SceneTracer& tracer = prepared.tracer;
  const Scene& s = tracer.scene();
  const double sigma_t = s.medium.extinction_per_m;
  std::optional<Hit> hit = tracer.intersect(eye, dir);
  if (hit && hit->ground && s.ground->albedo_texture)
    hit->albedo = ground_albedo(*s.ground->albedo_texture, eye.x + hit->t * dir.x, eye.z + hit->t * dir.z, dir, hit->t,
                                pixel_angle_rad);
  // The fog ends at the sky: surfaces beyond it are seen through the sky's distance of fog.
  const double fog_end = s.sky ? s.sky->distance_m : kInf;
  const std::optional<BulbHit> bulb = tracer.intersect_bulbs(eye, dir, hit ? hit->t : kInf);
  ReferenceSample out;
  double t_end = kInf;
  if (bulb) {
    const Light& l = s.lamps[bulb->light];
    t_end = bulb->t;
    out.radiance = l.intensity_w_sr / (M_PI * l.bulb_radius_m * l.bulb_radius_m) * std::exp(-sigma_t * t_end);
    out.alpha = 1.0;
  } else if (hit) {
    t_end = std::min(hit->t, fog_end);
    out.radiance = surface_radiance(prepared, eye + hit->t * dir, hit->normal, dir, hit->albedo) *
                   std::exp(-sigma_t * t_end);
    out.alpha = 1.0;
  } else if (s.sky) {
    t_end = s.sky->distance_m;
    out.radiance = sky_radiance(*s.sky, dir) * std::exp(-sigma_t * t_end);
    out.alpha = 1.0;
  } else {
    out.alpha = sigma_t > 0.0 ? 1.0 : 0.0;
  }
  if (s.medium.scattering_per_m() > 0.0) {
    const RayContext ray{prepared, tracer, settings, eye, dir, t_end};
    for (std::size_t i = 0; i < s.lamps.size(); ++i) {
      out.radiance += s.lamps[i].intensity_w_sr * point_airlight(ray, i);
    }
    if (s.sun) out.radiance += s.sun->irradiance_w_m2 * sun_airlight(ray, *s.sun);
  }
  return out;
}

// The frame's metadata as every renderer writes it (describe_frame), plus the reference's own
// settings.
void describe(Image& image, const Scene& s, const Camera& c, const ReferenceSettings& settings) {
  describe_frame(image, s, c, "reference");
  std::ostringstream tol;
  tol << settings.rel_tol;
  image.metadata["rel_tol"] = tol.str();
  image.metadata["visibility_samples"] = std::to_string(settings.visibility_samples);
  image.metadata["surface_airlight"] = settings.surface_airlight ? "on" : "off";
}

}  // namespace

void validate(const ReferenceSettings& s) {
  if (!std::isfinite(s.rel_tol) || !(s.rel_tol > 0.0) || !(s.rel_tol <= 0.1)) {
    throw std::invalid_argument("reference rel_tol: must be in (0, 0.1], got " + std::to_string(s.rel_tol));
  }
  if (s.threads < 0) throw std::invalid_argument("reference threads: must be >= 0 (0 = all cores)");
  if (s.visibility_samples < 16 || s.visibility_samples > (1 << 20)) {
    throw std::invalid_argument("reference visibility_samples: must be in [16, 1048576], got " +
                                std::to_string(s.visibility_samples));
  }
}

ReferenceSample reference_ray(const Scene& scene, const glm::dvec3& eye, const glm::dvec3& dir,
                              const ReferenceSettings& settings) {
  validate(scene);
  validate(settings);
  const Prepared prepared(scene, settings.surface_airlight);
  return trace(prepared, eye, glm::normalize(dir), settings, 0.0);
}

Image render_reference(const Scene& scene, const Camera& camera, const ReferenceSettings& settings) {
  validate(scene);
  validate(camera);
  validate(settings);
  const Prepared prepared(scene, settings.surface_airlight);
  Image image(camera.width, camera.height);
  describe(image, scene, camera, settings);
  const double pixel_angle = 2.0 * std::tan(0.5 * camera.fov_deg * M_PI / 180.0) / camera.width;  // at the centre
  detail::render_pixels(image, settings.threads, settings.progress, "reference", [&](int x, int y) {
    const auto px = trace(prepared, camera.eye, pixel_ray(camera, x, y), settings, pixel_angle);
    return glm::dvec4(px.radiance, px.alpha);
  });
  return image;
}

}  // namespace nimbus::render
