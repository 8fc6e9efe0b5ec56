// The half-angle slice renderer (cloud_renderer.hpp; Kniss et al. 2002/2003). Per frame: the
// lights drawn (the strongest at the clouds' centre), one pass per light (cloud_light_pass.cpp:
// the slicing axis and every slice's polygons inside each cloud's convex bound of non-zero density
// on the CPU, cloud_slice_geometry.cpp, then per slice an eye draw and a light draw), the later
// passes' radiance added into the first's, and with a scene underlay a composite pass
// (shaders/cloud_composite.frag.glsl) that puts the clouds and the fog in front of them over it.
#include "nimbus/render/clouds/cloud_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "cloud_light_pass.hpp"
#include "cloud_renderer_impl.hpp"
#include "cloud_slice_geometry.hpp"
#include "nimbus/render/core/blue_noise.hpp"
#include "nimbus/render/scene/metadata.hpp"
#include "nimbus/render/core/shader_contract.hpp"
#include "nimbus/render/gl/to_float.hpp"
#include "nimbus/render/gl/readback.hpp"

namespace nimbus::render {

using namespace cloud_detail;

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
    validate_period(c);
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
  s.cloud_hull_points.clear();
  for (const Placement& p : s.placements) s.cloud_hull_points.push_back(p.hull_vertices);
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
    s.cloud_hull_points[j].clear();
    for (const glm::dvec3& v : p.hull_vertices) {
      s.hull_points.push_back(v + o);
      s.cloud_hull_points[j].push_back(v + o);
    }
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

void CloudRenderer::Impl::bind_light_volume_grid() const {
  LightVolumeBlock b;
  b.world_min = to_float(lv_world_min);
  b.cell_m = to_float(lv_cell_m);
  b.cells = glm::vec3(lv_cells);
  b.light_dir = to_float(lv_light_dir);
  light_volume_ubo.update(b);
  light_volume_ubo.bind(contract::BLOCK_LIGHT_VOLUME);
}

void CloudRenderer::Impl::make_light_radiance(const glm::dvec3& eye, const glm::vec3& phase, GlTexture& target) {
  if (lr_cells != lv_cells) {  // a new grid: every texture made again at its size (`target` among them)
    light_radiance_tex.reset();
    for (GlTexture& t : copy_radiance_tex) t.reset();
    lr_cells = lv_cells;
  }
  if (target.id() == 0)
    target = make_texture_3d(GL_RGBA32F, 2 * lv_cells.x, lv_cells.y, lv_cells.z,
                             TextureParams{GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE, 1});
  if (!radiance_program) radiance_program.emplace(std::vector<std::string>{"light_volume_radiance.comp.glsl"});
  const ShaderProgram& p = *radiance_program;
  p.use();
  bind_light_volume_grid();
  p.set("u_lr_phase", phase);
  p.set("u_eye", to_float(eye));
  glBindTextureUnit(contract::UNIT_LIGHT_VOLUME, light_volume_tex.id());
  glBindImageTexture(contract::IMAGE_LIGHT_RADIANCE, target.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glDispatchCompute((lv_cells.x + 3) / 4, (lv_cells.y + 3) / 4, (lv_cells.z + 3) / 4);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  check_gl("the light volume's radiance toward the eye");
}

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

Image CloudRenderer::render(const Camera& camera, const Light& light, const CloudSliceSettings& settings,
                            const SceneUnderlay* underlay, CloudFrameStats* stats) {
  return render(camera, std::vector<Light>{light}, settings, underlay, stats);
}
namespace {

// A frame's inputs, checked before anything is drawn.
void validate_frame(const Camera& camera, const std::vector<Light>& lights, const CloudSliceSettings& settings,
                    const SceneUnderlay* underlay) {
  validate(camera);
  if (lights.empty()) throw std::invalid_argument("cloud renderer lights: the list is empty");
  for (const Light& l : lights) validate(l);
  validate(settings);
  if (!underlay) return;
  if (underlay->color_texture == 0) throw std::invalid_argument("scene underlay color_texture: must be a texture");
  if (underlay->distance_texture == 0) throw std::invalid_argument("scene underlay distance_texture: must be a texture");
  if (const Scene* scene = underlay->scene) {
    validate(*scene);
    if (scene->lamps.size() > static_cast<std::size_t>(contract::MAX_POINT_LIGHTS))
      throw std::invalid_argument("scene underlay scene: the cloud composite takes at most " +
                                  std::to_string(contract::MAX_POINT_LIGHTS) + " point lights, got " +
                                  std::to_string(scene->lamps.size()));
  }
}

// The middle of the clouds' bounds: where the lights are ranked and a lamp's axis is taken.
glm::dvec3 clouds_centre(const std::vector<glm::dvec3>& hull_points) {
  if (hull_points.empty()) return glm::dvec3(0.0);
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const glm::dvec3& p : hull_points) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  return 0.5 * (lo + hi);
}

// The lights drawn: the settings.max_lights strongest at the clouds' centre, one pass each.
std::vector<int> lights_drawn(const std::vector<Light>& lights, const glm::dvec3& centre,
                              const CloudSliceSettings& settings, bool light_volume) {
  const std::vector<int> order = strongest_lights(lights, centre, settings.max_lights);
  for (const int i : order)
    if (lights[i].kind == LightKind::Point && light_volume)
      throw std::invalid_argument(
          "cloud renderer lights: the light volume of multiple scattering is built for the sun; a lamp takes the "
          "octaves method (octaves 0: single scattering)");
  return order;
}

// The frame's metadata: the camera (and the underlay's scene), the clouds, the lights drawn and
// left out, the slicing settings and the first pass's axis (with the lamps' notes).
void describe_slice_frame(Image& img, const std::vector<CloudVolume>& clouds, const std::vector<Light>& lights,
                          const std::vector<int>& order, const CloudSliceSettings& settings, const Camera& camera,
                          const Scene* scene, const SliceAxis& first_axis, const std::string& lamp_notes) {
  if (scene) {
    describe_frame(img, *scene, camera, "cloud-slices");
  } else {
    img.metadata["method"] = "cloud-slices";
    img.metadata["camera"] = describe_camera(camera);
  }
  std::vector<Light> drawn_lights;
  for (const int i : order) drawn_lights.push_back(lights[i]);
  describe_clouds(img, clouds, drawn_lights);
  if (order.size() < lights.size()) {
    std::vector<Light> left;
    for (std::size_t i = 0; i < lights.size(); ++i)
      if (std::find(order.begin(), order.end(), static_cast<int>(i)) == order.end()) left.push_back(lights[i]);
    img.metadata["lights_left_out"] = describe_lights(left);
  }
  describe_slices(img, settings);
  std::ostringstream ax;
  ax.precision(9);
  ax << fmt3(first_axis.axis) << ", " << (first_axis.front_to_back ? "front-to-back (under)" : "back-to-front (over)")
     << ", half angle " << first_axis.half_angle_rad << " rad";
  if (!lamp_notes.empty()) ax << "; " << lamp_notes;
  img.metadata["slice_axis"] = ax.str();
}

CloudFrameStats frame_stats(GpuTimer& timer, int slices_drawn, const SliceAxis& first_axis, std::size_t passes) {
  CloudFrameStats st;
  timer.finish();
  st.light_ms = timer.ms(kLight);
  st.slices_ms = timer.ms(kEye);
  st.composite_ms = timer.ms(kComposite);
  st.light_fragments = timer.fragments(kLight);
  st.slices_fragments = timer.fragments(kEye);
  st.composite_fragments = timer.fragments(kComposite);
  st.total_ms = timer.total_ms();
  st.timing = timer.method() + " per pass";
  st.slices_drawn = slices_drawn;
  st.front_to_back = first_axis.front_to_back;
  st.half_angle_rad = first_axis.half_angle_rad;
  st.light_passes = static_cast<int>(passes);
  return st;
}

// The near pass's copies' radiance toward the eye (one texture per offset, at most
// kMaxCopyRadiance), and which texture each copy reads. Each costs an evaluation per cell of the
// light volume, where reading the volume per sample costs one per fragment: they are made when the
// pass's fragments (at most slices x pixels) outnumber the cells by kCellsPerFragment, else (and
// for more offsets) the pass reads the light volume per sample. Measured on the default view
// (docs/volume.md, "To the horizon"): a full-quality frame's slices 944 -> 777 ms with them, and
// the adaptive orbit's lowest level slower with them (the cells outweigh its fragments).
constexpr std::size_t kMaxCopyRadiance = 16;
constexpr double kCellsPerFragment = 4.0;
void make_copy_radiance(CloudRenderer::Impl& s, PassClouds& near, const Camera& camera, int slices,
                        const glm::vec3& phase) {
  if (!near.moved) return;
  std::vector<glm::dvec3> offsets;
  std::vector<int> which;
  for (const CloudInstance& i : near.instances) {
    if (i.offset_m == glm::dvec3(0.0)) {
      which.push_back(-1);
      continue;
    }
    const auto it = std::find(offsets.begin(), offsets.end(), i.offset_m);
    which.push_back(static_cast<int>(it - offsets.begin()));
    if (it == offsets.end()) offsets.push_back(i.offset_m);
  }
  const double cells = static_cast<double>(s.lv_cells.x) * s.lv_cells.y * s.lv_cells.z;
  const double fragments = static_cast<double>(slices) * camera.width * camera.height;
  if (offsets.size() > kMaxCopyRadiance || fragments < kCellsPerFragment * cells * static_cast<double>(offsets.size())) return;
  if (s.copy_radiance_tex.size() < offsets.size()) s.copy_radiance_tex.resize(offsets.size());
  for (std::size_t k = 0; k < offsets.size(); ++k)
    s.make_light_radiance(camera.eye - offsets[k], phase, s.copy_radiance_tex[k]);
  near.radiance = std::move(which);
}

}  // namespace

const ShaderProgram& CloudRenderer::Impl::composite_program_for(bool spots) {
  std::optional<ShaderProgram>& p = composite_programs[spots ? 1 : 0];
  if (!p)  // a scene without spots compiles their cones out (SPOTS, lib/light_list.glsl)
    p.emplace(std::vector<std::string>{"fullscreen.vert.glsl", "cloud_composite.frag.glsl"},
              std::string("#define SPOTS ") + (spots ? "1" : "0") + "\n");
  return *p;
}

Image CloudRenderer::Impl::composite(const SceneUnderlay& underlay, GpuTimer& timer, int w, int h, PixelDepths* depths) {
  const Scene* scene = underlay.scene;
  const ShaderProgram& cp = composite_program_for(scene != nullptr && any_spot(scene->lamps));
  const Medium fog = scene ? scene->medium : Medium{0.0, 0.0, Phase{}};
  cp.set("u_sigma_t", static_cast<float>(fog.extinction_per_m));
  cp.set("u_sigma_s", static_cast<float>(fog.scattering_per_m()));
  cp.set("u_phase_kind", phase_code(fog.phase.kind));
  cp.set("u_phase_g", static_cast<float>(fog.phase.g));
  lights_ubo.update(scene ? lights_block(*scene) : no_lights_block());
  lights_ubo.bind(contract::BLOCK_LIGHTS);
  const auto& tables = scene && scene->sky ? scene->sky->atmosphere : nullptr;
  if (tables) {
    if (!aerial || aerial->tables != tables) aerial = upload_atmosphere(tables);
    // The aerial perspective, and the horizon sky that the far ground fades into
    // (lib/far_ground_haze.glsl).
    bind_atmosphere_textures(*aerial);
  }
  sky_ubo.update(sky_block(scene && scene->sky ? &*scene->sky : nullptr, tables ? &*aerial : nullptr));
  sky_ubo.bind(contract::BLOCK_SKY);
  timer.time(kComposite, [&] {
    glBindFramebuffer(GL_FRAMEBUFFER, out_fbo.id());
    glViewport(0, 0, w, h);
    glBindTextureUnit(contract::UNIT_SCENE_COLOR, underlay.color_texture);
    glBindTextureUnit(contract::UNIT_CLOUD_COLOR, eye_color.id());
    glBindTextureUnit(contract::UNIT_CLOUD_DISTANCE, eye_distance.id());
    glBindTextureUnit(contract::UNIT_SCENE_DISTANCE, underlay.distance_texture);
    cp.use();
    draw_fullscreen_triangle(empty_vao);
  });
  check_gl("cloud composite");
  if (depths) {
    depths->width = w;
    depths->height = h;
    depths->values = read_rg(out_fbo, w, h, GL_COLOR_ATTACHMENT1);
  }
  return read_rgba(out_fbo, w, h);
}

Image CloudRenderer::render(const Camera& camera, const std::vector<Light>& all_lights,
                            const CloudSliceSettings& settings, const SceneUnderlay* underlay, CloudFrameStats* stats,
                            PixelDepths* depths) {
  validate_frame(camera, all_lights, settings, underlay);
  if (depths) *depths = PixelDepths{};
  Impl& s = *impl_;
  const bool light_volume = settings.multiple.method == MultipleScatteringMethod::LightVolume;
  if (light_volume && !has_light_volume())
    throw std::logic_error("cloud renderer: multiple-scattering method light-volume needs set_light_volume first");
  const glm::dvec3 centre = clouds_centre(s.hull_points);
  const std::vector<int> order = lights_drawn(all_lights, centre, settings, light_volume);
  // The copies drawn (cloud_tiles.hpp): without periodic clouds, every cloud where it is.
  CloudTilePlan tiles = plan_cloud_tiles(s.clouds, camera, settings.repeat_to_m);
  PassClouds near = pass_clouds(s, std::move(tiles.near));  // (make_copy_radiance fills its radiance)
  PassClouds far = pass_clouds(s, std::move(tiles.far));
  far.far = true;

  const int w = camera.width, h = camera.height;
  s.prepare_frame(w, h, settings, order.size() + (far.instances.empty() ? 0 : 1), underlay != nullptr);
  GpuTimer timer(kPassCount, stats != nullptr);
  const CameraBlock camera_values = camera_block(camera);
  s.camera_ubo.update(camera_values);
  s.camera_ubo.bind(contract::BLOCK_CAMERA);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glBlendEquation(GL_FUNC_ADD);
  const float zero[4] = {0, 0, 0, 0};
  timer.time(kEye, [&] {
    glClearNamedFramebufferfv(s.eye_fbo.id(), GL_COLOR, 0, zero);
    if (underlay) glClearNamedFramebufferfv(s.eye_fbo.id(), GL_COLOR, 1, zero);
  });

  // The light volume's radiance toward this eye, once for every slice, when the clouds share one
  // phase (in a sky they do); clouds of several phases read the volume per sample. The near
  // pass's copies get theirs too (a few); the far ones read the volume per sample.
  bool light_radiance = false;
  if (light_volume && !s.clouds.empty()) {
    const glm::vec3 phase = cloud_phase_lobes(s.clouds.front().optics.phase);
    const auto same = [&](const CloudVolume& c) { return cloud_phase_lobes(c.optics.phase) == phase; };
    if (std::all_of(s.clouds.begin(), s.clouds.end(), same)) {
      timer.time(kLight, [&] {
        s.make_light_radiance(camera.eye, phase, s.light_radiance_tex);
        make_copy_radiance(s, near, camera, settings.slices, phase);
      });
      light_radiance = true;
    }
  }
  // One pass per light over the near clouds, its radiance added into the first's; then the far
  // copies, lit by the first light alone, under them.
  const FrameContext frame{camera, camera_values, settings, light_volume, light_radiance, underlay, timer};
  int drawn = 0;
  SliceAxis first_axis;
  std::string lamp_notes;
  for (std::size_t pass = 0; pass < order.size(); ++pass) {
    const Light& light = all_lights[order[pass]];
    const LightPassPlan plan = plan_light_pass(s, near, camera, light, centre, settings, static_cast<int>(pass));
    if (pass == 0) first_axis = plan.axis;
    if (!plan.note.empty()) lamp_notes += (lamp_notes.empty() ? "" : "; ") + plan.note;
    drawn += draw_light_pass(s, near, frame, light, plan, pass == 0 ? PassTarget::Eye : PassTarget::AddToEye);
  }
  if (!far.instances.empty()) {
    const Light& light = all_lights[order.front()];
    const LightPassPlan plan = plan_light_pass(s, far, camera, light, centre, settings, 0);
    drawn += draw_light_pass(s, far, frame, light, plan, PassTarget::UnderEye);
  }

  Image img = underlay ? s.composite(*underlay, timer, w, h, depths) : read_rgba(s.eye_fbo, w, h);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  try {
    check_image(img, "cloud slices");
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  describe_slice_frame(img, s.clouds, all_lights, order, settings, camera, underlay ? underlay->scene : nullptr,
                       first_axis, lamp_notes);
  if (settings.repeat_to_m > 0.0) {
    std::ostringstream t;
    t << near.instances.size() << " near, " << far.instances.size() << " far (lit by the first light alone)";
    if (tiles.left_out > 0) t << ", " << tiles.left_out << " more in reach left out";
    img.metadata["periodic_copies"] = t.str();
  }
  if (stats) *stats = frame_stats(timer, drawn, first_axis, order.size());
  return img;
}

}  // namespace nimbus::render
