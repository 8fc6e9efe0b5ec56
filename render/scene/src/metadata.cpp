// Image metadata shared by every renderer (metadata.hpp).
#include "nimbus/render/scene/metadata.hpp"

#include <sstream>

#include "nimbus/render/core/world_axes.hpp"

namespace nimbus::render {

std::string fmt3(const glm::dvec3& v) {
  std::ostringstream s;
  s.precision(9);
  s << v.x << "," << v.y << "," << v.z;
  return s.str();
}

// Positions and directions are written in nimbus's Z-up world (world_axes.hpp), as the flags take them.
std::string describe_camera(const Camera& camera) {
  return "eye " + fmt3(render_to_world(camera.eye)) + " look_at " + fmt3(render_to_world(camera.look_at)) + " up " +
         fmt3(render_to_world(camera.up)) + " fov_deg " + std::to_string(camera.fov_deg) + " (z up)";
}

std::string describe_light(const Light& light) {
  if (light.kind == LightKind::Sun)
    return "sun towards " + fmt3(render_to_world(light.direction_to_sun)) + " (z up) E_w_m2 " + fmt3(light.irradiance_w_m2);
  std::ostringstream s;
  s.precision(9);
  s << "point " << fmt3(render_to_world(light.position_m)) << " (z up) I_w_sr " << fmt3(light.intensity_w_sr);
  if (is_spot(light))
    s << " spot axis " << fmt3(render_to_world(light.spot_axis)) << " inner_rad " << light.spot_inner_rad << " outer_rad "
      << light.spot_outer_rad;
  return s.str();
}

std::string describe_lights(const std::vector<Light>& lights) {
  std::string out;
  for (const Light& l : lights) out += (out.empty() ? "" : "; ") + describe_light(l);
  return out;
}

void describe_frame(Image& image, const Scene& scene, const Camera& camera, const std::string& method) {
  std::ostringstream s;
  s.precision(9);
  image.metadata["scene"] = scene.name;
  image.metadata["method"] = method;
  image.metadata["camera"] = describe_camera(camera);
  s << "extinction_per_m " << scene.medium.extinction_per_m << " albedo " << scene.medium.albedo << " phase "
    << to_string(scene.medium.phase);
  image.metadata["medium"] = s.str();
  std::string lights;
  for (const Light& l : scene.lamps) lights += (lights.empty() ? "" : "; ") + describe_light(l);
  if (scene.sun) lights += (lights.empty() ? "" : "; ") + describe_light(*scene.sun);
  image.metadata["lights"] = lights;
  if (scene.sky) {
    image.metadata["sky"] = "zenith " + fmt3(scene.sky->zenith_radiance_w_sr_m2) + " horizon " +
                            fmt3(scene.sky->horizon_radiance_w_sr_m2) + " distance_m " +
                            std::to_string(scene.sky->distance_m);
  }
}

void describe_clouds(Image& image, const std::vector<CloudVolume>& clouds, const Light& light) {
  describe_clouds(image, clouds, std::vector<Light>{light});
}

void describe_clouds(Image& image, const std::vector<CloudVolume>& clouds, const std::vector<Light>& lights) {
  std::string names, optics;
  for (const CloudVolume& c : clouds) {
    std::ostringstream o;
    o.precision(9);
    o << c.name << ": " << c.box.size[0] << "x" << c.box.size[1] << "x" << c.box.size[2] << " voxels, extinction_per_m "
      << c.optics.extinction_per_m << " albedo " << fmt3(c.optics.albedo) << " phase " << to_string(c.optics.phase)
      << " ambient " << fmt3(c.optics.ambient_radiance);
    names += (names.empty() ? "" : ", ") + c.name;
    optics += (optics.empty() ? "" : "; ") + o.str();
  }
  image.metadata["clouds"] = names;
  image.metadata["cloud_optics"] = optics;
  image.metadata["light"] = describe_lights(lights);
}

}  // namespace nimbus::render
