// The named light-shaft scenes of `nimbus render --scene NAME` (metres, y up, fog per metre),
// each with a default 1280x720 camera.
#include <cmath>
#include <stdexcept>

#include "nimbus/render/scene/daylight.hpp"
#include "nimbus/render/scene/scene.hpp"

namespace nimbus::render {
namespace {

Camera camera(glm::dvec3 eye, glm::dvec3 look_at, double fov_deg) {
  Camera c;
  c.eye = eye;
  c.look_at = look_at;
  c.up = {0.0, 1.0, 0.0};
  c.fov_deg = fov_deg;
  c.width = 1280;
  c.height = 720;
  c.near_m = 0.05;
  c.far_m = 2000.0;
  return c;
}

Medium medium(double extinction_per_m, double albedo, Phase phase) {
  Medium m;
  m.extinction_per_m = extinction_per_m;
  m.albedo = albedo;
  m.phase = phase;
  return m;
}

Box box(glm::dvec3 lo, glm::dvec3 hi, glm::dvec3 albedo) { return Box{lo, hi, Material{albedo}}; }

// Sun et al. fig. 8: three identical street lamps at 0, 16 and 32 m down a street, houses on
// the left, a garden wall on the right, a kiosk and a bench that cast shadows into the fog.
// Boxes 0-5 are the lamps (post, arm) in order.
Scene lamps() {
  Scene s;
  s.name = "lamps";
  s.medium = medium(0.04, 1.0, Phase{PhaseKind::Isotropic, 0.0});
  s.ground = GroundPlane{0.0, Material{{0.3, 0.3, 0.3}}};
  const glm::dvec3 grey{0.45, 0.45, 0.45};
  for (const double z : {0.0, -16.0, -32.0}) {
    // A 0.16 m square post 5.3 m high beside the street and an arm over it; the bulb
    // (r = 0.12 m) hangs 5 m up under the arm's end, so the arm shadows the fog above it.
    const glm::dvec3 dark{0.2, 0.2, 0.2};
    s.boxes.push_back(box({3.72, 0.0, z - 0.08}, {3.88, 5.3, z + 0.08}, dark));
    s.boxes.push_back(box({2.95, 5.2, z - 0.05}, {3.72, 5.3, z + 0.05}, dark));
    s.lamps.push_back(bulb_light({3.0, 5.0, z}, glm::dvec3{1.0, 0.85, 0.6} * 150.0, 0.12));
  }
  s.boxes.push_back(box({-14.0, 0.0, -45.0}, {-7.0, 12.0, -20.0}, {0.55, 0.5, 0.45}));  // houses
  s.boxes.push_back(box({-14.0, 0.0, -17.0}, {-7.0, 9.0, 2.0}, {0.5, 0.45, 0.4}));
  s.boxes.push_back(box({7.0, 0.0, -40.0}, {7.6, 3.0, 5.0}, grey));                       // wall
  s.boxes.push_back(box({1.2, 0.0, -17.2}, {2.4, 2.5, -15.0}, {0.35, 0.45, 0.35}));      // kiosk
  s.boxes.push_back(box({2.0, 0.0, -1.0}, {2.6, 0.5, 1.0}, {0.4, 0.3, 0.2}));             // bench
  s.camera = camera({-1.0, 1.7, 12.0}, {1.0, 2.6, -30.0}, 60.0);
  return s;
}

// Nine 0.8 m square pillars 2.5 m apart along x under a roof slab.
void add_colonnade(Scene& s) {
  const glm::dvec3 stone{0.6, 0.57, 0.5};
  for (int i = -4; i <= 4; ++i) {
    const double x = 2.5 * i;
    s.boxes.push_back(box({x - 0.4, 0.0, -0.4}, {x + 0.4, 6.0, 0.4}, stone));
  }
  s.boxes.push_back(box({-11.0, 6.0, -6.5}, {11.0, 6.6, 0.6}, stone));
}

// The colonnade as the front of a hall lit from inside: light leaves only between the
// pillars, in shafts toward the camera; HG g = 0.3 (forward scattering toward the viewer).
Scene colonnade() {
  Scene s;
  s.name = "colonnade";
  s.medium = medium(0.05, 1.0, Phase{PhaseKind::HenyeyGreenstein, 0.3});
  s.ground = GroundPlane{0.0, Material{{0.5, 0.5, 0.5}}};
  add_colonnade(s);
  const glm::dvec3 wall{0.5, 0.48, 0.45};
  s.boxes.push_back(box({-11.0, 0.0, -6.5}, {11.0, 6.0, -6.0}, wall));   // back
  s.boxes.push_back(box({-11.0, 0.0, -6.0}, {-10.4, 6.0, 0.4}, wall));   // left
  s.boxes.push_back(box({10.4, 0.0, -6.0}, {11.0, 6.0, 0.4}, wall));     // right
  s.lamps.push_back(bulb_light({0.0, 3.0, -3.2}, glm::dvec3{1.0, 0.9, 0.75} * 400.0, 0.1));
  s.camera = camera({3.0, 1.7, 16.0}, {0.0, 3.0, 0.0}, 60.0);
  return s;
}

// The open colonnade (no walls) with a low sun (16 degrees up) behind it: parallel shafts.
Scene colonnade_sun() {
  Scene s;
  s.name = "colonnade-sun";
  s.medium = medium(0.05, 1.0, Phase{PhaseKind::HenyeyGreenstein, 0.3});
  s.ground = GroundPlane{0.0, Material{{0.5, 0.5, 0.5}}};
  add_colonnade(s);
  s.sun = sun_light(glm::normalize(glm::dvec3{-0.35, 0.3, -1.0}), glm::dvec3{1.0, 0.95, 0.85} * 8.0);
  s.camera = camera({3.0, 1.7, 16.0}, {0.0, 3.0, 0.0}, 60.0);
  return s;
}

// Spheres floating around a point light: curved shadow silhouettes in the fog.
Scene spheres() {
  Scene s;
  s.name = "spheres";
  s.medium = medium(0.06, 0.9, Phase{PhaseKind::Schlick, 0.3});
  s.ground = GroundPlane{0.0, Material{{0.5, 0.5, 0.5}}};
  s.spheres = {
      Sphere{{-1.8, 3.2, 0.8}, 0.9, Material{{0.7, 0.3, 0.25}}},
      Sphere{{1.6, 2.4, -1.0}, 0.7, Material{{0.25, 0.5, 0.7}}},
      Sphere{{0.3, 4.8, -0.6}, 0.8, Material{{0.6, 0.6, 0.6}}},
      Sphere{{0.6, 1.3, 1.6}, 0.5, Material{{0.3, 0.65, 0.3}}},
      Sphere{{-0.8, 2.0, -2.2}, 0.6, Material{{0.7, 0.65, 0.3}}},
  };
  s.lamps.push_back(bulb_light({0.0, 3.0, 0.0}, glm::dvec3{1.0, 0.95, 0.9} * 300.0, 0.08));
  s.camera = camera({0.0, 2.2, 11.0}, {0.0, 2.6, 0.0}, 55.0);
  return s;
}

// Smooth deterministic terrain (metres): a ridge of five peaks 42-60 m high along z = -150 m,
// 50 m apart with notches about 15 m high between them, on gently undulating ground; lowest
// point 0.5 m.
double terrain_height(double x, double z) {
  auto bump = [](double dx, double dz, double rx, double rz) {
    return std::exp(-(dx * dx) / (rx * rx) - (dz * dz) / (rz * rz));
  };
  const double peaks[5][3] = {{-100.0, -145.0, 45.0}, {-50.0, -155.0, 58.0}, {0.0, -150.0, 50.0},
                              {50.0, -160.0, 60.0}, {100.0, -150.0, 42.0}};
  double y = 3.0 + 2.5 * std::sin(x / 31.0) * std::cos(z / 43.0);
  for (const auto& p : peaks) y += p[2] * bump(x - p[0], z - p[1], 22.0, 35.0);
  return y;
}

// 65 x 65 heightfield, 8 m apart (512 m square), over a ground plane at 0 m that closes the
// horizon beyond its edges; a low sun (about 10 degrees up) behind the ridge: the camera in
// the peaks' shadow sees lit sheets through the notches between shadow wedges, streaming
// toward it (forward scattering, HG g = 0.6).
Scene terrain() {
  Scene s;
  s.name = "terrain";
  s.medium = medium(0.006, 1.0, Phase{PhaseKind::HenyeyGreenstein, 0.6});
  Heightfield h;
  h.nx = h.nz = 65;
  h.spacing_m = 8.0;
  h.x0_m = h.z0_m = -256.0;
  h.heights_m.resize(static_cast<std::size_t>(h.nx) * h.nz);
  for (int iz = 0; iz < h.nz; ++iz) {
    for (int ix = 0; ix < h.nx; ++ix) {
      h.heights_m[static_cast<std::size_t>(iz) * h.nx + ix] =
          terrain_height(h.x0_m + ix * h.spacing_m, h.z0_m + iz * h.spacing_m);
    }
  }
  h.material = Material{{0.35, 0.4, 0.3}};
  s.terrain = h;
  s.ground = GroundPlane{0.0, Material{{0.35, 0.4, 0.3}}};
  s.sun = sun_light(glm::normalize(glm::dvec3{0.1, 0.18, -1.0}), glm::dvec3{1.0, 0.92, 0.8} * 6.0);
  // Eye 5 m above the ground 60 m south of the origin, looking north at the ridge.
  s.camera = camera({0.0, terrain_height(0.0, 60.0) + 5.0, 60.0}, {0.0, 30.0, -150.0}, 60.0);
  return s;
}

// One point light and nothing else: the airlight is Sun et al.'s, unoccluded, so ray marching
// must converge to the analytic value.
Scene open_scene() {
  Scene s;
  s.name = "open";
  s.medium = medium(0.05, 1.0, Phase{PhaseKind::Isotropic, 0.0});
  s.lamps.push_back(bulb_light({0.0, 3.0, 0.0}, glm::dvec3{100.0}, 0.05));
  s.camera = camera({0.0, 1.7, 10.0}, {1.0, 2.5, 0.0}, 60.0);
  return s;
}

// An afternoon sky for clouds: flat ground of fields, meadows and woods (its albedo
// texture, ground_albedo.hpp) reaching the horizon, the sun 33 degrees up to the right of the
// camera and a little ahead (clouds lit from the side, with bright edges and shafts below them),
// a thin forward-scattering haze (visibility about 400 km; the air itself adds the aerial
// perspective) for the shafts, and the physical sky
// (daylight.hpp) beyond 20 km, which also gives the sun its colour, seen from the camera's
// height. The camera stands 7 km south of the origin, where the presets put their clouds (at
// 0.4-11 km altitude).
Scene sky() {
  Scene s;
  s.name = "sky";
  s.medium = medium(1.0e-5, 0.9, Phase{PhaseKind::HenyeyGreenstein, 0.5});
  s.ground = GroundPlane{0.0, Material{{0.28, 0.3, 0.22}}};
  s.ground->albedo_texture = sky_ground_albedo();
  s.camera = camera({0.0, 2.0, 7000.0}, {0.0, 1500.0, 0.0}, 60.0);
  const Daylight d = daylight(glm::normalize(glm::dvec3{0.8, 0.55, -0.25}), s.camera.eye.y);
  s.sun = sun_light(d.sun.direction_to_sun, d.cloud_sun_irradiance_w_m2);
  s.sky = d.sky;
  s.camera.near_m = 1.0;
  s.camera.far_m = 40000.0;
  return s;
}

// The steaming teacup of Hoffmann 2007 ("Plazierung") under a street lamp on a misty night:
// a cup on a cafe table, its tea's surface at the origin where the `steam` preset rises, and a
// street lamp 3.2 m up and 3 m behind it (its post 2 m to the left, out of the default view), so
// that the steam is lit from behind and glows,
// forward-scattered, toward the camera. No sun, no sky: the lamp alone lights steam, table and
// mist. The steam is hand-sized, so the scene asks for a denser cloud extinction.
Scene steam_lamp() {
  Scene s;
  s.name = "steam-lamp";
  s.medium = medium(0.006, 1.0, Phase{PhaseKind::Isotropic, 0.0});
  s.ground = GroundPlane{-0.84, Material{{0.25, 0.24, 0.23}}};
  const glm::dvec3 wood{0.45, 0.3, 0.18}, china{0.85, 0.85, 0.82}, iron{0.15, 0.15, 0.15};
  s.boxes.push_back(box({-0.45, -0.125, -0.45}, {0.45, -0.095, 0.45}, wood));  // table top
  for (const double x : {-0.4, 0.37})
    for (const double z : {-0.4, 0.37}) s.boxes.push_back(box({x, -0.84, z}, {x + 0.03, -0.125, z + 0.03}, wood));
  s.boxes.push_back(box({-0.07, -0.095, -0.07}, {0.07, -0.088, 0.07}, china));  // saucer
  s.boxes.push_back(box({-0.04, -0.088, -0.04}, {0.04, -0.004, 0.04}, china));  // cup, the tea 4 mm down
  s.boxes.push_back(box({-2.04, -0.84, -3.04}, {-1.97, 3.4, -2.97}, iron));     // lamp post, out of view
  s.boxes.push_back(box({-1.97, 3.4, -3.03}, {0.7, 3.45, -2.98}, iron));        // its arm
  s.lamps.push_back(bulb_light({0.6, 3.25, -3.0}, glm::dvec3{1.0, 0.78, 0.5} * 150.0, 0.08));
  s.camera = camera({-0.12, 0.1, 1.0}, {0.0, 0.17, 0.0}, 40.0);
  s.camera.near_m = 0.02;
  s.camera.far_m = 200.0;
  s.cloud_extinction_per_m = 40.0;
  return s;
}

// The street of lamps() lit by spots (light.hpp), as street lights are: each shines down and a
// little out over the street, full within 35 degrees and gone by 55, so that the fog glows in
// cones and the ground in pools of light.
Scene spots() {
  Scene s = lamps();
  s.name = "spots";
  for (Light& l : s.lamps) {
    l.spot_axis = glm::dvec3(-0.25, -1.0, 0.0);
    l.spot_inner_rad = 35.0 * M_PI / 180.0;
    l.spot_outer_rad = 55.0 * M_PI / 180.0;
  }
  return s;
}

}  // namespace

std::vector<std::string> scene_names() {
  return {"lamps", "spots", "colonnade", "colonnade-sun", "spheres", "terrain", "open", "sky", "steam-lamp"};
}

Scene make_scene(const std::string& name) {
  if (name == "lamps") return lamps();
  if (name == "spots") return spots();
  if (name == "colonnade") return colonnade();
  if (name == "colonnade-sun") return colonnade_sun();
  if (name == "spheres") return spheres();
  if (name == "terrain") return terrain();
  if (name == "open") return open_scene();
  if (name == "sky") return sky();
  if (name == "steam-lamp") return steam_lamp();
  std::string known;
  for (const std::string& n : scene_names()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("scene: unknown name '" + name + "' (known: " + known + ")");
}

}  // namespace nimbus::render
