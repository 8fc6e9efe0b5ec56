// Validation of the light-shaft scene: every field checked, errors name the field
// (e.g. "scene.boxes[2].max_m: ...") so a bad preset or command line is easy to trace.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nimbus/render/scene/scene.hpp"

namespace nimbus::render {
namespace {

bool finite3(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

[[noreturn]] void fail(const std::string& field, const std::string& why) {
  throw std::invalid_argument("scene." + field + ": " + why);
}

std::string at(const std::string& list, std::size_t i) {
  return list + "[" + std::to_string(i) + "]";
}

void check_material(const Material& m, const std::string& field) {
  const glm::dvec3& a = m.albedo;
  if (!finite3(a) || a.x < 0.0 || a.y < 0.0 || a.z < 0.0 || a.x > 1.0 || a.y > 1.0 || a.z > 1.0) {
    fail(field + ".material.albedo", "must be in [0, 1] per channel");
  }
}

void check_non_negative3(const glm::dvec3& v, const std::string& field) {
  if (!finite3(v) || v.x < 0.0 || v.y < 0.0 || v.z < 0.0) fail(field, "must be finite and >= 0");
}

bool inside_box(const Box& b, const glm::dvec3& p) {
  return p.x > b.min_m.x && p.x < b.max_m.x && p.y > b.min_m.y && p.y < b.max_m.y &&
         p.z > b.min_m.z && p.z < b.max_m.z;
}

// Points strictly inside an occluder (a light buried in a wall, the eye inside a pillar)
// would make the whole image dark: reported as an error instead.
void check_not_buried(const Scene& s, const glm::dvec3& p, const std::string& field) {
  for (std::size_t i = 0; i < s.boxes.size(); ++i) {
    if (inside_box(s.boxes[i], p)) fail(field, "lies inside " + at("boxes", i));
  }
  for (std::size_t i = 0; i < s.spheres.size(); ++i) {
    if (glm::length(p - s.spheres[i].centre_m) < s.spheres[i].radius_m) {
      fail(field, "lies inside " + at("spheres", i));
    }
  }
}

}  // namespace

void validate(const Scene& s) {
  try {
    validate(s.medium);
  } catch (const std::invalid_argument& e) {
    fail("medium", e.what());
  }
  if (s.cloud_extinction_per_m && !(std::isfinite(*s.cloud_extinction_per_m) && *s.cloud_extinction_per_m > 0.0))
    fail("cloud_extinction_per_m", "must be finite and > 0");
  if (s.ground) {
    if (!std::isfinite(s.ground->height_m)) fail("ground.height_m", "must be finite");
    check_material(s.ground->material, "ground");
  }
  if (s.terrain) {
    const Heightfield& t = *s.terrain;
    if (!std::isfinite(t.x0_m)) fail("terrain.x0_m", "must be finite");
    if (!std::isfinite(t.z0_m)) fail("terrain.z0_m", "must be finite");
    if (!std::isfinite(t.spacing_m) || !(t.spacing_m > 0.0)) fail("terrain.spacing_m", "must be > 0");
    if (t.nx < 2) fail("terrain.nx", "must be >= 2, got " + std::to_string(t.nx));
    if (t.nz < 2) fail("terrain.nz", "must be >= 2, got " + std::to_string(t.nz));
    if (t.heights_m.size() != static_cast<std::size_t>(t.nx) * static_cast<std::size_t>(t.nz)) {
      fail("terrain.heights_m", "must hold nx * nz = " + std::to_string(t.nx * t.nz) +
                                    " values, got " + std::to_string(t.heights_m.size()));
    }
    for (std::size_t i = 0; i < t.heights_m.size(); ++i) {
      if (!std::isfinite(t.heights_m[i])) fail(at("terrain.heights_m", i), "must be finite");
    }
    check_material(t.material, "terrain");
  }
  for (std::size_t i = 0; i < s.boxes.size(); ++i) {
    const Box& b = s.boxes[i];
    const std::string f = at("boxes", i);
    if (!finite3(b.min_m)) fail(f + ".min_m", "must be finite");
    if (!finite3(b.max_m)) fail(f + ".max_m", "must be finite");
    if (!(b.max_m.x > b.min_m.x && b.max_m.y > b.min_m.y && b.max_m.z > b.min_m.z)) {
      fail(f + ".max_m", "must be > min_m in every axis");
    }
    check_material(b.material, f);
  }
  for (std::size_t i = 0; i < s.spheres.size(); ++i) {
    const Sphere& sp = s.spheres[i];
    const std::string f = at("spheres", i);
    if (!finite3(sp.centre_m)) fail(f + ".centre_m", "must be finite");
    if (!std::isfinite(sp.radius_m) || !(sp.radius_m > 0.0)) fail(f + ".radius_m", "must be > 0");
    check_material(sp.material, f);
  }
  if (s.lamps.empty() && !s.sun) fail("lamps", "the scene has no light (no lamp, no sun)");
  for (std::size_t i = 0; i < s.lamps.size(); ++i) {
    const Light& l = s.lamps[i];
    const std::string f = at("lamps", i);
    if (l.kind != LightKind::Point) fail(f, "must be a lamp (the sun is the scene's sun)");
    if (!finite3(l.spot_axis)) fail(f + ".spot_axis", "must be finite (zero: a lamp that shines every way)");
    if (!valid_spot_cone(l))
      fail(f + ".spot_inner_rad", "a spot's cone must have 0 < spot_inner_rad <= spot_outer_rad <= pi");
    if (!std::isfinite(l.min_distance_m) || !(l.min_distance_m > 0.0)) fail(f + ".min_distance_m", "must be finite and > 0");
    if (!finite3(l.position_m)) fail(f + ".position_m", "must be finite");
    check_non_negative3(l.intensity_w_sr, f + ".intensity_w_sr");
    if (!std::isfinite(l.bulb_radius_m) || !(l.bulb_radius_m >= 0.0)) {
      fail(f + ".bulb_radius_m", "must be finite and >= 0 (0: no visible bulb)");
    }
    check_not_buried(s, l.position_m, f + ".position_m");
  }
  if (s.sky) {
    check_non_negative3(s.sky->zenith_radiance_w_sr_m2, "sky.zenith_radiance_w_sr_m2");
    check_non_negative3(s.sky->horizon_radiance_w_sr_m2, "sky.horizon_radiance_w_sr_m2");
    if (!std::isfinite(s.sky->distance_m) || !(s.sky->distance_m > 0.0)) fail("sky.distance_m", "must be finite and > 0");
  }
  if (s.sun) {
    if (s.sun->kind != LightKind::Sun) fail("sun", "must be the sun, not a lamp");
    if (!finite3(s.sun->direction_to_sun) || !(glm::length(s.sun->direction_to_sun) > 0.0)) {
      fail("sun.direction_to_sun", "must be finite and non-zero");
    }
    check_non_negative3(s.sun->irradiance_w_m2, "sun.irradiance_w_m2");
  }
  try {
    validate(s.camera);
  } catch (const std::invalid_argument& e) {
    fail("camera", e.what());
  }
  check_not_buried(s, s.camera.eye, "camera.eye");
  for (std::size_t i = 0; i < s.lamps.size(); ++i) {
    if (glm::length(s.camera.eye - s.lamps[i].position_m) <= s.lamps[i].bulb_radius_m) {
      fail("camera.eye", "lies inside the bulb of " + at("lamps", i));
    }
  }
  if (s.ground) {
    for (std::size_t i = 0; i < s.lamps.size(); ++i) {
      if ((s.lamps[i].position_m.y > s.ground->height_m) != (s.camera.eye.y > s.ground->height_m)) {
        fail(at("lamps", i) + ".position_m", "is on the other side of the ground plane from the camera");
      }
    }
  }
}

glm::dvec3 sky_mean_radiance(const Sky& sky) {
  if (sky.atmosphere) return sky.atmosphere->sky_mean_radiance_w_sr_m2;
  return 0.5 * (sky.zenith_radiance_w_sr_m2 + sky.horizon_radiance_w_sr_m2);
}

glm::dvec3 sky_irradiance(const Sky& sky, const glm::dvec3& n) {
  const glm::dvec3 mean = sky.atmosphere ? sky.atmosphere->sky_irradiance_up_w_m2 / M_PI
                                         : 0.5 * (sky.zenith_radiance_w_sr_m2 + sky.horizon_radiance_w_sr_m2);
  return M_PI * mean * (0.5 * (1.0 + std::clamp(n.y, -1.0, 1.0)));
}

glm::dvec3 sky_radiance(const Sky& sky, const glm::dvec3& dir) {
  if (sky.atmosphere) return table_sky_radiance(*sky.atmosphere, dir);
  const double w = std::sqrt(std::max(dir.y, 0.0));
  return sky.horizon_radiance_w_sr_m2 + (sky.zenith_radiance_w_sr_m2 - sky.horizon_radiance_w_sr_m2) * w;
}

}  // namespace nimbus::render
