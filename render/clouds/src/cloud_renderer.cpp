// The half-angle slice renderer (cloud_renderer.hpp; Kniss et al. 2002/2003). Per frame: the
// slicing axis and every slice's polygons inside each cloud's convex bound of non-zero density
// on the CPU (cloud_slice_geometry.cpp), then per slice
// an eye pass (shaders/cloud_slice.frag.glsl: lit from the light buffer, composited under or
// over) and a light pass (shaders/cloud_light.frag.glsl: adds the slab's optical depth, after
// an optional forward-scattering blur), and with a scene underlay a composite pass
// (shaders/cloud_composite.frag.glsl) that puts the clouds and the fog in front of them over it.
#include "nimbus/render/clouds/cloud_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>
#include <stdexcept>
#include <utility>

#include "cloud_slice_geometry.hpp"
#include "nimbus/render/core/blue_noise.hpp"
#include "nimbus/render/core/shader_contract.hpp"
#include "nimbus/render/gl/atmosphere_textures.hpp"
#include "nimbus/render/gl/gpu_timer.hpp"
#include "nimbus/render/gl/readback.hpp"
#include "nimbus/render/gl/resources.hpp"
#include "nimbus/render/gl/to_float.hpp"
#include "nimbus/render/gl/uniform_blocks.hpp"
#include "nimbus/render/gl/shader_program.hpp"
#include "nimbus/render/core/metadata.hpp"

namespace nimbus::render {
namespace {

using namespace cloud_detail;

constexpr int kJitterTile = 64;        // blue-noise tile side, pixels (power of two)
constexpr std::uint32_t kJitterSeed = 5;

// The frame's passes as GpuTimer slots.
enum Pass { kLight = 0, kEye, kComposite, kPassCount };

}  // namespace

// Where set_clouds put a cloud; set_motion moves it from here.
struct Placement {
  glm::dmat4 index_to_world{1.0};
  openvdb::math::Transform::Ptr transform;
  glm::dvec3 world_min{0.0}, world_max{0.0};
  glm::dmat4 world_to_texture{1.0};
  ConvexHull hull;
  std::vector<glm::dvec3> hull_vertices;
};

struct CloudRenderer::Impl {
  std::vector<CloudVolume> clouds;         // as drawn (moved)
  std::vector<VolumeTexture> textures;
  std::vector<std::optional<VolumeTexture>> next_textures;  // the next keyframe, if any
  std::vector<Placement> placements;
  std::vector<ConvexHull> hulls;           // where each cloud's density can be non-zero
  std::vector<glm::dvec3> hull_points;     // all their vertices
  ShaderProgram light_program{{"cloud_light.vert.glsl", "cloud_light.frag.glsl"}, "#define LAMP 0\n"};
  ShaderProgram lamp_light_program{{"cloud_light.vert.glsl", "cloud_light.frag.glsl"}, "#define LAMP 1\n"};
  ShaderProgram blur_program{{"fullscreen.vert.glsl", "cloud_light_blur.frag.glsl"}};
  std::optional<ShaderProgram> accumulate_program;  // the second light's pass on
  std::map<std::tuple<bool, int, bool, bool>, ShaderProgram> eye_programs;  // by (underlay, octaves, light volume, lamp)
  std::optional<ShaderProgram> composite_program;
  std::optional<AtmosphereTextures> aerial;  // the underlay scene's physical sky, uploaded once per table set
  UniformBuffer<CameraBlock> camera_ubo;
  UniformBuffer<LightsBlock> lights_ubo;
  UniformArray<CloudBlock> cloud_ubo;  // one block per cloud, refilled every frame
  GlVertexArray empty_vao, mesh_vao;
  GlBuffer mesh_buffer;
  std::size_t mesh_capacity = 0;  // vertices
  GlTexture jitter;

  int light_res = 0;
  GlTexture light_tex[2];
  GlFramebuffer light_fbo[2];

  int eye_w = 0, eye_h = 0;
  bool eye_has_distance = false;
  GlTexture eye_color, eye_distance, out_color;
  GlFramebuffer eye_fbo, out_fbo;
  // The second light's pass on draws here, then adds its radiance into eye_color.
  int pass_w = 0, pass_h = 0;
  GlTexture pass_color, pass_distance;
  GlFramebuffer pass_fbo;

  // The light volume (set_light_volume): fluence, flux and second moment side by side along x.
  GlTexture light_volume_tex;
  glm::dvec3 lv_world_min{0.0};
  glm::dvec3 lv_cell_m{0.0};
  glm::dvec3 lv_light_dir{0.0, -1.0, 0.0};
  glm::ivec3 lv_cells{0};

  const ShaderProgram& eye_program(bool underlay, int octaves, bool light_volume, bool lamp);
  void upload_mesh(const SliceMesh& mesh);
  void ensure_light_buffers(int res);
  void ensure_eye_buffers(int w, int h, bool distance);
  void ensure_pass_buffers(int w, int h);
};

const ShaderProgram& CloudRenderer::Impl::eye_program(bool underlay, int octaves, bool light_volume, bool lamp) {
  const auto key = std::make_tuple(underlay, octaves, light_volume, lamp);
  auto it = eye_programs.find(key);
  if (it == eye_programs.end()) {
    const std::string defines = "#define UNDERLAY " + std::string(underlay ? "1" : "0") + "\n#define OCTAVES " +
                                std::to_string(octaves) + "\n#define MS_VOLUME " + (light_volume ? "1" : "0") +
                                "\n#define LAMP " + (lamp ? "1" : "0") + "\n";
    it = eye_programs.emplace(key, ShaderProgram({"cloud_slice.vert.glsl", "cloud_slice.frag.glsl"}, defines)).first;
  }
  return it->second;
}

void CloudRenderer::Impl::upload_mesh(const SliceMesh& mesh) {
  if (mesh.vertices.size() > mesh_capacity) {
    mesh_capacity = std::max<std::size_t>(mesh.vertices.size(), 2 * mesh_capacity);
    mesh_buffer = make_buffer(static_cast<GLsizeiptr>(mesh_capacity * sizeof(glm::vec3)));
    mesh_vao = make_vertex_array();
    const GLuint vao = mesh_vao.id();
    glVertexArrayVertexBuffer(vao, 0, mesh_buffer.id(), 0, sizeof(glm::vec3));
    glEnableVertexArrayAttrib(vao, 0);
    glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, 0, 0);
  }
  if (!mesh.vertices.empty())
    glNamedBufferSubData(mesh_buffer.id(), 0, static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(glm::vec3)),
                         mesh.vertices.data());
  check_gl("uploading slice polygons");
}

void CloudRenderer::Impl::ensure_light_buffers(int res) {
  if (res == light_res) return;
  for (int i = 0; i < 2; ++i) {
    // Linear filtering; border 0 outside the footprint (no cloud there).
    light_tex[i] = make_texture_2d(GL_R32F, res, res, TextureParams{GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_BORDER, 1});
    light_fbo[i] = make_framebuffer({{GL_COLOR_ATTACHMENT0, light_tex[i].id()}});
  }
  light_res = res;
}

void CloudRenderer::Impl::ensure_eye_buffers(int w, int h, bool distance) {
  if (w == eye_w && h == eye_h && distance == eye_has_distance) return;
  const TextureParams nearest{GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE, 1};
  eye_color = make_texture_2d(GL_RGBA32F, w, h, nearest);
  if (distance) {
    eye_distance = make_texture_2d(GL_RGBA32F, w, h, nearest);
    eye_fbo = make_framebuffer({{GL_COLOR_ATTACHMENT0, eye_color.id()}, {GL_COLOR_ATTACHMENT1, eye_distance.id()}});
    out_color = make_texture_2d(GL_RGBA32F, w, h, nearest);
    out_fbo = make_framebuffer({{GL_COLOR_ATTACHMENT0, out_color.id()}});
  } else {
    eye_distance.reset();
    out_color.reset();
    out_fbo.reset();
    eye_fbo = make_framebuffer({{GL_COLOR_ATTACHMENT0, eye_color.id()}});
  }
  eye_w = w;
  eye_h = h;
  eye_has_distance = distance;
}

void CloudRenderer::Impl::ensure_pass_buffers(int w, int h) {
  if (w == pass_w && h == pass_h) return;
  const TextureParams nearest{GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE, 1};
  pass_color = make_texture_2d(GL_RGBA32F, w, h, nearest);
  pass_distance = make_texture_2d(GL_RGBA32F, w, h, nearest);  // written by the underlay variant, not read
  pass_fbo = make_framebuffer({{GL_COLOR_ATTACHMENT0, pass_color.id()}, {GL_COLOR_ATTACHMENT1, pass_distance.id()}});
  pass_w = w;
  pass_h = h;
}

CloudRenderer::CloudRenderer(std::vector<CloudVolume> clouds, GLenum format) : impl_(std::make_unique<Impl>()) {
  set_clouds(std::move(clouds), format);
  Impl& s = *impl_;
  s.empty_vao = make_vertex_array();
  const std::vector<float> tile = blue_noise_tile(kJitterTile, kJitterSeed);
  s.jitter = make_texture_2d(GL_R32F, kJitterTile, kJitterTile, TextureParams{GL_NEAREST, GL_NEAREST, GL_REPEAT, 1});
  glTextureSubImage2D(s.jitter.id(), 0, 0, 0, kJitterTile, kJitterTile, GL_RED, GL_FLOAT, tile.data());
  check_gl("cloud renderer set-up");
}

void CloudRenderer::set_clouds(std::vector<CloudVolume> clouds, GLenum format) {
  if (clouds.empty()) throw std::invalid_argument("cloud renderer clouds: the list is empty");
  std::vector<VolumeTexture> textures;
  std::vector<std::optional<VolumeTexture>> next_textures;
  std::vector<Placement> placements;
  std::vector<ConvexHull> hulls;
  std::vector<glm::dvec3> hull_points;
  for (const CloudVolume& c : clouds) {
    try {
      validate(c.optics);
      if (!c.transform) throw std::invalid_argument("it has no transform");
      textures.push_back(upload_volume(c.box, *c.transform, format));
      next_textures.emplace_back();
      if (!c.next_box.values.empty()) {
        if (c.next_box.origin != c.box.origin || c.next_box.size != c.box.size)
          throw std::invalid_argument("its next keyframe must lie on the same box");
        next_textures.back() = upload_volume(c.next_box, *c.transform, format);
      }
      if (!(c.blend >= 0.0 && c.blend <= 1.0)) throw std::invalid_argument("keyframe blend must be in [0, 1]");
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("cloud '" + c.name + "': " + e.what());
    }
    hulls.push_back(cloud_hull(c));
    const std::vector<glm::dvec3> v = hull_vertices(hulls.back());
    hull_points.insert(hull_points.end(), v.begin(), v.end());
    placements.push_back(Placement{c.index_to_world, c.transform, c.world_min, c.world_max,
                                   textures.back().world_to_texture, hulls.back(), v});
  }
  Impl& s = *impl_;
  s.textures = std::move(textures);
  s.next_textures = std::move(next_textures);
  s.placements = std::move(placements);
  s.hulls = std::move(hulls);
  s.hull_points = std::move(hull_points);
  s.clouds = std::move(clouds);
}

void CloudRenderer::set_optics(const CloudOptics& optics) {
  validate(optics);
  for (CloudVolume& c : impl_->clouds) c.optics = optics;
}

void CloudRenderer::set_motion(const std::vector<CloudMotion>& motion) {
  Impl& s = *impl_;
  if (motion.size() != s.clouds.size())
    throw std::invalid_argument("cloud renderer motion: " + std::to_string(motion.size()) + " entries for " +
                                std::to_string(s.clouds.size()) + " clouds");
  for (std::size_t j = 0; j < motion.size(); ++j) {
    const CloudMotion& m = motion[j];
    if (!(m.blend >= 0.0 && m.blend <= 1.0) || (m.blend > 0.0 && !s.next_textures[j]))
      throw std::invalid_argument("cloud '" + s.clouds[j].name + "': keyframe blend must be in [0, 1], and 0 without a next keyframe");
    if (!std::isfinite(m.offset_m.x) || !std::isfinite(m.offset_m.y) || !std::isfinite(m.offset_m.z))
      throw std::invalid_argument("cloud '" + s.clouds[j].name + "': translation must be finite");
  }
  s.hull_points.clear();
  for (std::size_t j = 0; j < motion.size(); ++j) {
    const Placement& p = s.placements[j];
    const glm::dvec3 o = motion[j].offset_m;
    // From the placement, never from the last frame: the same offset gives the same numbers.
    CloudVolume& c = s.clouds[j];
    c.index_to_world = p.index_to_world;
    c.transform = p.transform;
    c.world_min = p.world_min;
    c.world_max = p.world_max;
    apply_motion(c, motion[j]);
    VolumeTexture& t = s.textures[j];
    // world_to_texture * T(-o): only the translation column changes.
    t.world_to_texture = p.world_to_texture;
    t.world_to_texture[3] = p.world_to_texture * glm::dvec4(-o, 1.0);
    t.world_min = c.world_min;
    t.world_max = c.world_max;
    s.hulls[j] = translated(p.hull, o);
    for (const glm::dvec3& v : p.hull_vertices) s.hull_points.push_back(v + o);
  }
}

void CloudRenderer::set_light_volume(const LightVolume& volume) {
  if (!light_volume_is_consistent(volume) || !(glm::length(volume.light_direction) > 0.5))
    throw std::invalid_argument("cloud renderer light volume: its sizes, cell, light direction and values do not agree");
  Impl& s = *impl_;
  const int nx = volume.size[0], ny = volume.size[1], nz = volume.size[2];
  // Five sections along x (lib/cloud_light_volume.glsl): (fluence RGB, Q xx), (flux xyz, Q yy),
  // (Q xy, xz, yz, h), (gradient xyz, 0), (f_1, mu_1, f_2, mu_2).
  constexpr int kSections = 5;
  std::vector<float> texels(static_cast<std::size_t>(kSections * nx) * ny * nz * 4, 0.0f);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const std::size_t src = static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * (j + static_cast<std::size_t>(ny) * k);
        const std::size_t row = static_cast<std::size_t>(kSections * nx) * (j + static_cast<std::size_t>(ny) * k);
        float* a = &texels[4 * (row + i)];
        float* b = &texels[4 * (row + nx + i)];
        float* c = &texels[4 * (row + 2 * nx + i)];
        float* d = &texels[4 * (row + 3 * nx + i)];
        float* e4 = &texels[4 * (row + 4 * nx + i)];
        if (!volume.gradient.empty()) {
          for (int e = 0; e < 3; ++e) d[e] = volume.gradient[4 * src + e];
          c[3] = volume.gradient[4 * src + 3];
        }
        if (!volume.lobes.empty())
          for (int e = 0; e < 4; ++e) e4[e] = volume.lobes[4 * src + e];
        const float* q = &volume.quadrupole[5 * src];
        for (int e = 0; e < 3; ++e) {
          a[e] = volume.fluence_rgb[3 * src + e];
          b[e] = volume.flux_xyz[3 * src + e];
          c[e] = q[2 + e];
        }
        a[3] = q[0];
        b[3] = q[1];
      }
  // Each blend of the animated sky uploads a volume of the same grid: keep the texture's storage.
  if (s.light_volume_tex.id() == 0 || s.lv_cells != glm::ivec3(nx, ny, nz))
    s.light_volume_tex = make_texture_3d(GL_RGBA32F, kSections * nx, ny, nz, TextureParams{GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE, 1});
  glTextureSubImage3D(s.light_volume_tex.id(), 0, 0, 0, 0, kSections * nx, ny, nz, GL_RGBA, GL_FLOAT, texels.data());
  check_gl("uploading the light volume");
  s.lv_world_min = volume.world_min;
  s.lv_cell_m = volume.cell_m;
  s.lv_light_dir = glm::normalize(volume.light_direction);
  s.lv_cells = glm::ivec3(nx, ny, nz);
}

bool CloudRenderer::has_light_volume() const { return impl_->light_volume_tex.id() != 0; }

void CloudRenderer::move_light_volume(const glm::dvec3& world_min) {
  if (!has_light_volume()) throw std::logic_error("cloud renderer: no light volume to move");
  if (!(std::isfinite(world_min.x) && std::isfinite(world_min.y) && std::isfinite(world_min.z))) throw std::invalid_argument("cloud renderer light volume: its corner is not finite");
  impl_->lv_world_min = world_min;
}

CloudRenderer::~CloudRenderer() = default;

const std::vector<CloudVolume>& CloudRenderer::clouds() const { return impl_->clouds; }

std::vector<const VolumeTexture*> CloudRenderer::textures() const {
  std::vector<const VolumeTexture*> out;
  for (const VolumeTexture& t : impl_->textures) out.push_back(&t);
  return out;
}

std::vector<const VolumeTexture*> CloudRenderer::next_textures() const {
  std::vector<const VolumeTexture*> out;
  for (const std::optional<VolumeTexture>& t : impl_->next_textures) out.push_back(t ? &*t : nullptr);
  return out;
}

Image CloudRenderer::render(const Camera& camera, const CloudLight& light, const CloudSliceSettings& settings,
                            const SceneUnderlay* underlay, CloudFrameStats* stats) {
  return render(camera, std::vector<CloudLight>{light}, settings, underlay, stats);
}

Image CloudRenderer::render(const Camera& camera, const std::vector<CloudLight>& all_lights,
                            const CloudSliceSettings& settings, const SceneUnderlay* underlay, CloudFrameStats* stats) {
  validate(camera);
  if (all_lights.empty()) throw std::invalid_argument("cloud renderer lights: the list is empty");
  for (const CloudLight& l : all_lights) validate(l);
  validate(settings);
  const Scene* scene = underlay ? underlay->scene : nullptr;
  if (underlay) {
    if (underlay->color_texture == 0) throw std::invalid_argument("scene underlay color_texture: must be a texture");
    if (underlay->distance_texture == 0)
      throw std::invalid_argument("scene underlay distance_texture: must be a texture");
    if (scene) {
      validate(*scene);
      if (scene->point_lights.size() > static_cast<std::size_t>(contract::MAX_POINT_LIGHTS))
        throw std::invalid_argument("scene underlay scene: the cloud composite takes at most " +
                                    std::to_string(contract::MAX_POINT_LIGHTS) + " point lights, got " +
                                    std::to_string(scene->point_lights.size()));
    }
  }
  Impl& s = *impl_;
  const int w = camera.width, h = camera.height;
  const std::size_t n_clouds = s.clouds.size();
  const bool light_volume = settings.multiple.method == MultipleScatteringMethod::LightVolume;
  if (light_volume && !has_light_volume())
    throw std::logic_error("cloud renderer: multiple-scattering method light-volume needs set_light_volume first");

  // The lights drawn: the strongest at the middle of the clouds' bounds, one pass each.
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const glm::dvec3& p : s.hull_points) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const glm::dvec3 centre = s.hull_points.empty() ? glm::dvec3(0.0) : 0.5 * (lo + hi);
  const std::vector<int> order = strongest_lights(all_lights, centre, settings.max_lights);
  for (const int i : order)
    if (all_lights[i].kind == CloudLightKind::Point && light_volume)
      throw std::invalid_argument(
          "cloud renderer lights: the light volume of multiple scattering is built for the sun; a lamp takes the "
          "octaves method (octaves 0: single scattering)");

  s.ensure_light_buffers(settings.light_res);
  s.ensure_eye_buffers(w, h, underlay != nullptr);
  if (order.size() > 1) {
    s.ensure_pass_buffers(w, h);
    if (!s.accumulate_program)
      s.accumulate_program.emplace(std::vector<std::string>{"fullscreen.vert.glsl", "cloud_accumulate.frag.glsl"});
  }
  if (underlay && !s.composite_program)
    s.composite_program.emplace(std::vector<std::string>{"fullscreen.vert.glsl", "cloud_composite.frag.glsl"});
  const bool blur = settings.blur_cone_rad > 0.0;
  GpuTimer timer(kPassCount, stats != nullptr);
  const CameraFrame frame = camera_frame(camera);
  const CameraBlock camera_values = camera_block(camera);
  s.camera_ubo.update(camera_values);
  s.camera_ubo.bind(contract::BLOCK_CAMERA);
  const MultipleScattering& ms = settings.multiple;
  const double f = static_cast<double>(settings.frame);

  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glBlendEquation(GL_FUNC_ADD);
  const float zero[4] = {0, 0, 0, 0};
  timer.time(kEye, [&] {
    glClearNamedFramebufferfv(s.eye_fbo.id(), GL_COLOR, 0, zero);
    if (underlay) glClearNamedFramebufferfv(s.eye_fbo.id(), GL_COLOR, 1, zero);
  });

  int drawn = 0;
  SliceAxis first_axis;
  std::string axes_text;
  for (std::size_t pass = 0; pass < order.size(); ++pass) {
    const CloudLight& light = all_lights[order[pass]];
    const bool lamp = light.kind == CloudLightKind::Point;
    // Geometry: the axis, the planes and every polygon (Kniss et al. 2003). For a lamp, the axis
    // takes the light's direction at the clouds' centre (Kniss et al. for local lights).
    const glm::dvec3 l = lamp ? (glm::length(centre - light.position_m) > 0.0 ? glm::normalize(centre - light.position_m)
                                                                             : glm::dvec3(0.0, -1.0, 0.0))
                              : -glm::normalize(light.direction_to_light);
    const SliceAxis axis = choose_slice_axis(frame.forward, l, settings.branch);
    if (pass == 0) first_axis = axis;
    const SlicePlanes planes = slice_planes(s.hull_points, axis.axis, settings.slices);
    // A jittered sample lies up to dt / 2 = d / (2 |dot(ray, s)|) along its ray from the plane, so
    // a ray whose plane point misses the hull can still sample density inside it: the polygons
    // are cut from the hulls grown by that much (the steepest ray at the image's corners).
    double margin_m = 0.0;
    if (settings.jitter) {
      double min_cos = 1.0;
      for (int c = 0; c < 4; ++c) {
        const glm::dvec3 r = pixel_ray(camera, (c & 1) ? w - 1 : 0, (c & 2) ? h - 1 : 0);
        min_cos = std::min(min_cos, std::abs(glm::dot(r, axis.axis)));
      }
      margin_m = std::min(0.5 / std::max(min_cos, 0.125), 4.0) * planes.spacing_m;
    }
    std::vector<ConvexHull> hulls;
    for (const ConvexHull& hull : s.hulls) hulls.push_back(grown(hull, margin_m));
    const SliceMesh mesh = build_slice_mesh(hulls, axis.axis, planes);
    s.upload_mesh(mesh);
    // The slab between two planes is spacing / dot(l, s) thick along the light (issue 5: d / cos);
    // for a lamp, per fragment along each of its rays.
    const double light_slab_m = planes.spacing_m / std::max(glm::dot(l, axis.axis), 1e-3);
    // The light buffer's frame: the sun's orthographic one, or the lamp's perspective one.
    LightFrame lf;
    LampFrame lamp_f;
    double texel_m[2];
    if (!lamp) {
      lf = light_frame(s.hull_points, l, settings.light_res);
      texel_m[0] = lf.texel_m.x;
      texel_m[1] = lf.texel_m.y;
    } else {
      lamp_f = lamp_frame(s.hull_points, light.position_m, l, settings.light_res);
      const double r = glm::length(centre - light.position_m);  // a texel's width at the clouds' centre
      texel_m[0] = std::max(r, 1e-9) * lamp_f.texel_tan.x;
      texel_m[1] = std::max(r, 1e-9) * lamp_f.texel_tan.y;
      // How many slice planes lie on the lamp's near side (they see no shadow from the buffer).
      const double lamp_s = glm::dot(axis.axis, light.position_m);
      int near_side = 0;
      for (int k = 0; k < planes.count; ++k) near_side += planes.first_m + k * planes.spacing_m <= lamp_s;
      std::ostringstream a;
      a << "lamp " << pass << ": " << near_side << " of " << planes.count << " slices on its near side"
        << (lamp_f.clipped ? ", light buffer clipped" : "");
      axes_text += (axes_text.empty() ? "" : "; ") + a.str();
    }
    const ShaderProgram& eye = s.eye_program(underlay != nullptr, light_volume ? 0 : ms.octaves, light_volume, lamp);
    const ShaderProgram& lp = lamp ? s.lamp_light_program : s.light_program;

    // Pass-constant uniforms: the slicing geometry and the light.
    eye.set("u_view_proj", camera_values.view_proj);
    eye.set("u_slice_axis", to_float(axis.axis));
    eye.set("u_spacing_m", static_cast<float>(planes.spacing_m));
    eye.set("u_octave_abc", glm::vec3(static_cast<float>(ms.occlusion), static_cast<float>(ms.contribution),
                                      static_cast<float>(ms.eccentricity)));
    if (lamp) {
      for (const ShaderProgram* p : {&eye, &lp}) {
        p->set("u_lamp_position", to_float(light.position_m));
        p->set("u_lamp_intensity", to_float(light.intensity_w_sr));
        const bool spot = glm::length(light.spot_axis) > 0.0;
        p->set("u_lamp_spot", glm::vec4(spot ? to_float(glm::normalize(light.spot_axis)) : glm::vec3(0.0f), spot ? 1.0f : 0.0f));
        p->set("u_lamp_cos", glm::vec2(static_cast<float>(std::cos(light.spot_outer_rad)),
                                       static_cast<float>(std::cos(light.spot_inner_rad))));
        p->set("u_lamp_min_distance", static_cast<float>(light.min_distance_m));
        p->set("u_slice_axis", to_float(axis.axis));
        p->set("u_spacing_m", static_cast<float>(planes.spacing_m));
      }
      eye.set("u_world_to_light_clip", to_float(lamp_f.world_to_clip));
    } else {
      eye.set("u_world_to_light", to_float(lf.world_to_uv));
      eye.set("u_light_slab_m", static_cast<float>(light_slab_m));
      eye.set("u_light_dir", to_float(l));
      eye.set("u_irradiance", to_float(light.irradiance_w_m2));
      eye.set("u_luv_eye", glm::vec2(lf.world_to_uv * glm::dvec4(camera.eye, 1.0)));
    }
    if (light_volume) {
      eye.set("u_lv_world_min", to_float(s.lv_world_min));
      eye.set("u_lv_cell_m", to_float(s.lv_cell_m));
      eye.set("u_lv_cells", glm::vec3(s.lv_cells));
      eye.set("u_lv_light_dir", to_float(s.lv_light_dir));
    }
    // This frame's jitter: the tile shifted along the R2 sequence, its values rotated by the
    // golden ratio (Cranley-Patterson), so every pixel sees a new offset each frame.
    eye.set("u_jitter_offset", glm::ivec2(static_cast<int>(kJitterTile * (f * 0.7548776662466927 - std::floor(f * 0.7548776662466927))),
                                          static_cast<int>(kJitterTile * (f * 0.5698402909980532 - std::floor(f * 0.5698402909980532)))));
    eye.set("u_jitter_shift", static_cast<float>(f * 0.6180339887498949 - std::floor(f * 0.6180339887498949)));
    eye.set("u_jitter_on", settings.jitter ? 1.0f : 0.0f);
    if (underlay) eye.set("u_fog_sigma_t", scene ? static_cast<float>(scene->medium.extinction_per_m) : 0.0f);
    lp.set("u_view_proj", to_float(lamp ? lamp_f.world_to_clip : lf.world_to_clip));
    if (blur) {
      // Kniss's cone: the light spreads by radius (slab along the light) tan(cone) per slice; a
      // disk of radius R has variance R^2 / 4 per axis, which the 5-tap kernel reproduces. For a
      // lamp, the texels and the slab are taken at the clouds' centre.
      glm::ivec2 step;
      glm::vec2 weight;
      for (int a = 0; a < 2; ++a) {
        const double r = light_slab_m * std::tan(settings.blur_cone_rad) / texel_m[a];  // texels
        step[a] = std::max(1, static_cast<int>(std::ceil(r / std::sqrt(2.0))));
        weight[a] = static_cast<float>(std::min(0.25, r * r / (8.0 * step[a] * step[a])));
      }
      s.blur_program.set("u_step", step);
      s.blur_program.set("u_weight", weight);
    }

    // Every cloud's block for this pass (its optics, and what depends on the eye and the slabs);
    // the ambient sky light enters once, in the first pass.
    std::vector<CloudBlock> blocks(n_clouds);
    for (std::size_t j = 0; j < n_clouds; ++j) {
      const CloudVolume& c = s.clouds[j];
      const VolumeTexture& t = s.textures[j];
      CloudBlock& b = blocks[j];
      b.world_to_texture = to_float(t.world_to_texture);
      b.tc_eye = glm::vec3(t.world_to_texture * glm::dvec4(camera.eye, 1.0));
      b.sigma_t = static_cast<float>(c.optics.extinction_per_m);
      b.albedo = to_float(c.optics.albedo);
      b.ambient = settings.ambient && pass == 0 ? to_float(c.optics.ambient_radiance) : glm::vec3(0.0f);
      b.phase = glm::vec3(static_cast<float>(c.optics.phase.g_forward), static_cast<float>(c.optics.phase.g_back),
                          static_cast<float>(c.optics.phase.forward_weight));
      b.tau_per_density = static_cast<float>(c.optics.extinction_per_m * light_slab_m);
      b.blend = s.next_textures[j] ? static_cast<float>(c.blend) : 0.0f;
    }
    s.cloud_ubo.update(blocks);
    std::size_t bound = n_clouds;  // none yet
    auto bind_cloud = [&](std::size_t j) {
      s.cloud_ubo.bind(contract::BLOCK_CLOUD, j);
      glBindTextureUnit(contract::UNIT_CLOUD_DENSITY, s.textures[j].texture.id());
      const VolumeTexture& next = s.next_textures[j] ? *s.next_textures[j] : s.textures[j];
      glBindTextureUnit(contract::UNIT_CLOUD_DENSITY_NEXT, next.texture.id());
    };
    auto draw_slice = [&](int k) {
      for (std::size_t j = 0; j < n_clouds; ++j) {
        const std::size_t idx = static_cast<std::size_t>(k) * n_clouds + j;
        if (mesh.count[idx] == 0) continue;
        if (bound != j) bind_cloud(j);
        bound = j;
        glDrawArrays(GL_TRIANGLES, mesh.first[idx], mesh.count[idx]);
      }
    };

    // The first pass draws into the eye buffer; later ones into their own, added in after.
    const GlFramebuffer& target = pass == 0 ? s.eye_fbo : s.pass_fbo;
    int cur = 0;
    timer.time(kLight, [&] { glClearNamedFramebufferfv(s.light_fbo[0].id(), GL_COLOR, 0, zero); });
    if (pass > 0)
      timer.time(kEye, [&] {
        glClearNamedFramebufferfv(s.pass_fbo.id(), GL_COLOR, 0, zero);
        glClearNamedFramebufferfv(s.pass_fbo.id(), GL_COLOR, 1, zero);
      });
    glBindTextureUnit(contract::UNIT_JITTER, s.jitter.id());
    if (light_volume) glBindTextureUnit(contract::UNIT_LIGHT_VOLUME, s.light_volume_tex.id());
    if (underlay) glBindTextureUnit(contract::UNIT_SCENE_DISTANCE, underlay->distance_texture);
    glBindVertexArray(s.mesh_vao.id());
    for (int k = 0; k < planes.count; ++k) {
      bool any = false;
      for (std::size_t j = 0; j < n_clouds; ++j) any = any || mesh.count[static_cast<std::size_t>(k) * n_clouds + j] > 0;
      if (any) {
        ++drawn;
        timer.time(kEye, [&] {
          glBindFramebuffer(GL_FRAMEBUFFER, target.id());
          glViewport(0, 0, w, h);
          glEnable(GL_BLEND);
          if (axis.front_to_back) {
            glBlendFunc(GL_ONE_MINUS_DST_ALPHA, GL_ONE);  // "under"
          } else {
            glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // "over"
          }
          glBindTextureUnit(contract::UNIT_LIGHT_BUFFER, s.light_tex[cur].id());
          eye.use();
          draw_slice(k);
        });
      }
      if (k + 1 == planes.count) break;  // nothing reads the light buffer after the last slice
      if (!any && !blur) continue;
      timer.time(kLight, [&] {
        glViewport(0, 0, s.light_res, s.light_res);
        if (blur) {  // next = blur(previous) + this slice
          const int next = 1 - cur;
          glBindFramebuffer(GL_FRAMEBUFFER, s.light_fbo[next].id());
          glDisable(GL_BLEND);
          glBindTextureUnit(contract::UNIT_LIGHT_BUFFER, s.light_tex[cur].id());
          s.blur_program.use();
          draw_fullscreen_triangle(s.empty_vao);
          glBindVertexArray(s.mesh_vao.id());
          cur = next;
        } else {
          glBindFramebuffer(GL_FRAMEBUFFER, s.light_fbo[cur].id());
        }
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);
        lp.use();
        draw_slice(k);
      });
    }
    if (pass > 0) {  // this light's radiance into the eye buffer; its coverage is already there
      timer.time(kEye, [&] {
        glBindFramebuffer(GL_FRAMEBUFFER, s.eye_fbo.id());
        glViewport(0, 0, w, h);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);
        glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);
        glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glBindTextureUnit(contract::UNIT_CLOUD_COLOR, s.pass_color.id());
        s.accumulate_program->use();
        draw_fullscreen_triangle(s.empty_vao);
        glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glColorMaski(1, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      });
    }
    glDisable(GL_BLEND);
    check_gl("cloud slices");
  }

  Image img;
  if (underlay) {
    const ShaderProgram& cp = *s.composite_program;
    const Medium fog = scene ? scene->medium : Medium{0.0, 0.0, Phase{}};
    cp.set("u_sigma_t", static_cast<float>(fog.extinction_per_m));
    cp.set("u_sigma_s", static_cast<float>(fog.scattering_per_m()));
    cp.set("u_phase_kind", phase_code(fog.phase.kind));
    cp.set("u_phase_g", static_cast<float>(fog.phase.g));
    s.lights_ubo.update(scene ? lights_block(*scene) : no_lights_block());
    s.lights_ubo.bind(contract::BLOCK_LIGHTS);
    const auto& tables = scene && scene->sky ? scene->sky->atmosphere : nullptr;
    if (tables) {
      if (!s.aerial || s.aerial->tables != tables) s.aerial = upload_atmosphere(tables);
      bind_aerial_perspective(cp, *s.aerial);
    } else {
      cp.set("u_aerial_on", 0);
    }
    timer.time(kComposite, [&] {
      glBindFramebuffer(GL_FRAMEBUFFER, s.out_fbo.id());
      glViewport(0, 0, w, h);
      glBindTextureUnit(contract::UNIT_SCENE_COLOR, underlay->color_texture);
      glBindTextureUnit(contract::UNIT_CLOUD_COLOR, s.eye_color.id());
      glBindTextureUnit(contract::UNIT_CLOUD_DISTANCE, s.eye_distance.id());
      glBindTextureUnit(contract::UNIT_SCENE_DISTANCE, underlay->distance_texture);
      cp.use();
      draw_fullscreen_triangle(s.empty_vao);
    });
    check_gl("cloud composite");
    img = read_rgba(s.out_fbo, w, h);
  } else {
    img = read_rgba(s.eye_fbo, w, h);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);

  try {
    check_image(img, "cloud slices");
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  if (scene) {
    describe_frame(img, *scene, camera, "cloud-slices");
  } else {
    img.metadata["method"] = "cloud-slices";
    img.metadata["camera"] = describe_camera(camera);
  }
  std::vector<CloudLight> drawn_lights;
  for (const int i : order) drawn_lights.push_back(all_lights[i]);
  describe_clouds(img, s.clouds, drawn_lights);
  if (order.size() < all_lights.size()) {
    std::vector<CloudLight> left;
    for (std::size_t i = 0; i < all_lights.size(); ++i)
      if (std::find(order.begin(), order.end(), static_cast<int>(i)) == order.end()) left.push_back(all_lights[i]);
    img.metadata["lights_left_out"] = describe_lights(left);
  }
  describe_slices(img, settings);
  std::ostringstream ax;
  ax.precision(9);
  ax << fmt3(first_axis.axis) << ", " << (first_axis.front_to_back ? "front-to-back (under)" : "back-to-front (over)")
     << ", half angle " << first_axis.half_angle_rad << " rad";
  if (!axes_text.empty()) ax << "; " << axes_text;
  img.metadata["slice_axis"] = ax.str();
  if (stats) {
    CloudFrameStats st;
    timer.finish();
    st.light_ms = timer.ms(kLight);
    st.slices_ms = timer.ms(kEye);
    st.composite_ms = timer.ms(kComposite);
    st.total_ms = timer.total_ms();
    st.timing = timer.method() + " per pass";
    st.slices_drawn = drawn;
    st.front_to_back = first_axis.front_to_back;
    st.half_angle_rad = first_axis.half_angle_rad;
    st.light_passes = static_cast<int>(order.size());
    *stats = st;
  }
  return img;
}

}  // namespace nimbus::render
