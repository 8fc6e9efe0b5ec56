// The frame pipeline (frame_renderer.hpp).
#include "nimbus/render/frame/frame_renderer.hpp"

#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>

#include "nimbus/base/cancel.hpp"
#include "nimbus/render/clouds/cloud_shadow.hpp"
#include "nimbus/render/reference/light_volume_builder.hpp"
#include "nimbus/render/scene/metadata.hpp"
#include "nimbus/render/core/render_settings.hpp"

namespace nimbus::render {

namespace {

// The GL texture format of the clouds' density textures.
GLenum gl_format(VolumeFormat f) { return f == VolumeFormat::Float ? GL_R32F : GL_R16F; }

}  // namespace

void validate(const FrameSettings& s) {
  try {
    validate(s.slices);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("frame settings slices: ") + e.what());
  }
  try {
    validate(s.reference);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("frame settings reference: ") + e.what());
  }
  try {
    validate(s.path_tracer);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("frame settings path_tracer: ") + e.what());
  }
  if (s.shafts.kind == ShaftMethod::Kind::Reference)
    throw std::invalid_argument("frame settings shafts: the scene under GPU clouds needs a GPU method, not reference");
  check_setting(Setting::CloudShadowRes, s.cloud_shadow_res, "frame settings cloud_shadow_res");
  if (s.volume_format != VolumeFormat::Half && s.volume_format != VolumeFormat::Float)
    throw std::invalid_argument("frame settings volume_format: must be Half or Float");
}

FrameRenderer::FrameRenderer(const FrameDescription& frame)
    : FrameRenderer(frame.scene, frame.lights, frame.settings) {
  validate(frame.optics);
  optics_ = frame.optics;
}

FrameRenderer::FrameRenderer(std::optional<Scene> scene, const Light& light, const FrameSettings& settings)
    : FrameRenderer(std::move(scene), std::vector<Light>{light}, settings) {}

FrameRenderer::FrameRenderer(std::optional<Scene> scene, std::vector<Light> lights, const FrameSettings& settings)
    : scene_(std::move(scene)), settings_(settings) {
  validate(settings_);
  if (is_cpu_method(settings_.method) && scene_)
    throw std::invalid_argument("the cloud " + to_string(settings_.method) + " renders clouds alone, without a scene");
  int suns = 0;
  for (const Light& l : lights) {
    validate(l);
    if (l.kind == LightKind::Sun) {
      if (++suns > 1) throw std::invalid_argument("frame lights: at most one sun");
      set_light(l);
    } else if (scene_) {
      // A lamp in a scene is one of its lamps, a spot among them: the fog, the surfaces and the
      // clouds see it.
      scene_->lamps.push_back(l);
    } else {
      lamps_.push_back(l);
    }
  }
  if (cloud_lights().empty()) throw std::invalid_argument("frame lights: nothing lights the clouds (no sun, no lamp)");
  if (settings_.method == CloudMethod::PathTrace && !lamps_.empty())
    throw std::invalid_argument("frame lights: the cloud path tracer takes the sun only, not lamps");
  if (scene_) validate(*scene_);
}

FrameRenderer::~FrameRenderer() = default;

Light FrameRenderer::light() const { return sun().value_or(Light{}); }

std::vector<Light> FrameRenderer::cloud_lights() const {
  std::vector<Light> out;
  if (has_sun()) out.push_back(*sun());
  const std::vector<Light>& lamps = scene_ ? scene_->lamps : lamps_;
  out.insert(out.end(), lamps.begin(), lamps.end());
  return out;
}

void FrameRenderer::set_light(const Light& light) {
  validate(light);
  if (light.kind != LightKind::Sun) throw std::invalid_argument("frame light: set_light moves the sun; this is a lamp");
  const std::optional<Light>& old = sun();
  if (!old || glm::normalize(light.direction_to_sun) != glm::normalize(old->direction_to_sun)) light_volume_stale_ = true;
  const bool moved = !old || old->direction_to_sun != light.direction_to_sun || old->irradiance_w_m2 != light.irradiance_w_m2;
  (scene_ ? scene_->sun : sun_) = light;
  if (scene_ && moved) shaft_renderer_.reset();  // its sun shadow map follows the sun
}

void FrameRenderer::set_sun(const SunSetup& setup) {
  set_light(setup.sun);
  if (scene_ && setup.sky) set_sky(*setup.sky);
}

void FrameRenderer::set_sky(const Sky& sky) {
  if (!scene_) throw std::invalid_argument("frame sky: there is no scene to put it in");
  const bool changed = !scene_->sky || scene_->sky->zenith_radiance_w_sr_m2 != sky.zenith_radiance_w_sr_m2 ||
                       scene_->sky->horizon_radiance_w_sr_m2 != sky.horizon_radiance_w_sr_m2 ||
                       scene_->sky->distance_m != sky.distance_m || scene_->sky->atmosphere != sky.atmosphere;
  Scene next = *scene_;
  next.sky = sky;
  validate(next);
  scene_ = std::move(next);
  if (changed) shaft_renderer_.reset();
}

void FrameRenderer::set_clouds(std::vector<CloudVolume> clouds) {
  light_volume_stale_ = true;
  if (optics_)
    for (CloudVolume& c : clouds) c.optics = *optics_;
  if (is_cpu_method(settings_.method)) {
    if (clouds.empty()) throw std::invalid_argument("frame clouds: the list is empty");
    reference_clouds_ = std::move(clouds);
    reference_moved_ = reference_clouds_;
  } else if (cloud_renderer_) {
    cloud_renderer_->set_clouds(std::move(clouds), gl_format(settings_.volume_format));
  } else {
    cloud_renderer_ = std::make_unique<CloudRenderer>(std::move(clouds), gl_format(settings_.volume_format));
  }
}

const std::vector<CloudVolume>& FrameRenderer::clouds() const {
  return cloud_renderer_ ? cloud_renderer_->clouds() : reference_moved_;
}

void FrameRenderer::set_motion(const std::vector<CloudMotion>& motion) {
  if (!is_cpu_method(settings_.method)) {
    if (!cloud_renderer_) throw std::logic_error("frame renderer: no clouds set");
    cloud_renderer_->set_motion(motion);
    light_volume_stale_ = true;
    return;
  }
  if (motion.size() != reference_clouds_.size())
    throw std::invalid_argument("frame motion: " + std::to_string(motion.size()) + " entries for " +
                                std::to_string(reference_clouds_.size()) + " clouds");
  std::vector<CloudVolume> moved = reference_clouds_;
  for (std::size_t j = 0; j < moved.size(); ++j) apply_motion(moved[j], motion[j]);
  reference_moved_ = std::move(moved);
}

void FrameRenderer::set_optics(const CloudOptics& optics) {
  validate(optics);
  if (optics_) optics_ = optics;
  if (cloud_renderer_) cloud_renderer_->set_optics(optics);
  light_volume_stale_ = true;
  for (CloudVolume& c : reference_clouds_) c.optics = optics;
  for (CloudVolume& c : reference_moved_) c.optics = optics;
}

void FrameRenderer::set_settings(const FrameSettings& settings) {
  validate(settings);
  if (settings.method != settings_.method) throw std::invalid_argument("frame settings method: cannot change");
  if (settings.volume_format != settings_.volume_format)
    throw std::invalid_argument("frame settings volume_format: cannot change");
  const bool same_shafts = settings.shaft_settings == settings_.shaft_settings;
  settings_ = settings;
  if (!same_shafts) shaft_renderer_.reset();
}

namespace {

// The image metadata's "light_volume": its grid, photons, seed, lobes and fits. No build time: a
// frame's file depends on its inputs alone, byte for byte, whoever renders it when (docs/farm.md).
std::string describe_light_volume(const LightVolume& v) {
  char depth[64];
  std::snprintf(depth, sizeof depth, "diffused deeper than %g transport mean free paths", v.diffusion_depth);
  std::string traced = v.diffusion_depth > 0.0 ? depth : "all light traced";
  char similar[96];
  std::snprintf(similar, sizeof similar, ", similar medium deeper than %g transport mean free paths", v.similarity_depth);
  if (v.similarity_depth > 0.0) traced += similar;
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "%dx%dx%d cells of %.6g x %.6g x %.6g m, %lld photons, seed %llu, %d lobe orders, %s, %s, built on the CPU",
                v.size[0], v.size[1], v.size[2], v.cell_m.x, v.cell_m.y, v.cell_m.z, static_cast<long long>(v.photons),
                static_cast<unsigned long long>(v.seed), v.lobes.empty() ? 0 : v.lobe_orders,
                v.gradient.empty() ? "no fits" : "linear fits", traced.c_str());
  return buf;
}

}  // namespace

void FrameRenderer::set_light_volume(const LightVolume& volume) {
  if (!cloud_renderer_) throw std::logic_error("frame renderer: a light volume needs the Slices method and its clouds set first");
  cloud_renderer_->set_light_volume(volume);
  light_volume_given_ = true;
  light_volume_description_ = describe_light_volume(volume) + " (given)";
}

void FrameRenderer::move_light_volume(const glm::dvec3& world_min) {
  if (!cloud_renderer_) throw std::logic_error("frame renderer: no light volume to move (no clouds set)");
  cloud_renderer_->move_light_volume(world_min);
}

bool FrameRenderer::has_light_volume() const { return cloud_renderer_ && cloud_renderer_->has_light_volume(); }

double FrameRenderer::update_light_volume() {
  const MultipleScattering& ms = settings_.slices.multiple;
  if (ms.method != MultipleScatteringMethod::LightVolume || light_volume_given_) return 0.0;
  if (!has_sun())
    throw std::invalid_argument("frame settings slices: the light volume of multiple scattering is built from the sun, and "
                                "there is none; lamps take the octaves method");
  if (!light_volume_stale_ && cloud_renderer_->has_light_volume() && ms.light_volume == light_volume_built_) return 0.0;
  const LightVolume v = build_light_volume(cloud_renderer_->clouds(), light(), ms.light_volume);
  cloud_renderer_->set_light_volume(v);
  light_volume_stale_ = false;
  light_volume_built_ = ms.light_volume;
  light_volume_description_ = describe_light_volume(v);
  return 1000.0 * v.build_seconds;
}

Image FrameRenderer::render(const Camera& camera, FrameStats* stats, PixelDepths* depths) {
  validate(camera);
  if (depths) *depths = PixelDepths{};
  FrameStats st;
  Image image;
  if (settings_.method == CloudMethod::Reference) {
    if (reference_clouds_.empty()) throw std::logic_error("frame renderer: no clouds set");
    image = render_cloud_reference(reference_moved_, camera, cloud_lights(), settings_.reference);
    st.device = "CPU (double precision)";
  } else if (settings_.method == CloudMethod::PathTrace) {
    if (reference_clouds_.empty()) throw std::logic_error("frame renderer: no clouds set");
    image = render_cloud_path_traced(reference_moved_, camera, light(), settings_.path_tracer).image;
    st.device = "CPU (double precision, path traced)";
  } else {
    if (!cloud_renderer_) throw std::logic_error("frame renderer: no clouds set");
    const bool had = cloud_renderer_->has_light_volume() &&
                     (light_volume_given_ || (!light_volume_stale_ && settings_.slices.multiple.light_volume == light_volume_built_));
    // The GL passes below are not polled inside (a draw cannot stop half-way); between them, a
    // poll of the call's stop (cancel.hpp) keeps a stop within one pass.
    const std::stop_token stop = current_stop_token();
    st.light_volume_build_ms = update_light_volume();
    st.light_volume_rebuilt = settings_.slices.multiple.method == MultipleScatteringMethod::LightVolume && !had;
    throw_if_stopped(stop);
    char buf[256];
    if (scene_) {
      if (!shaft_renderer_) shaft_renderer_ = std::make_unique<ShaftRenderer>(*scene_, settings_.shaft_settings);
      if (!shadow_builder_) shadow_builder_ = std::make_unique<CloudShadowBuilder>();
      // The clouds' shadow on the scene is the sun's; under lamps alone the clouds cast none.
      std::optional<CloudShadowMap> map;
      if (has_sun())
        map = shadow_builder_->build(cloud_renderer_->clouds(), cloud_renderer_->textures(), light(),
                                     settings_.cloud_shadow_res, cloud_renderer_->next_textures());
      shaft_renderer_->set_cloud_shadow(map ? &*map : nullptr);
      try {
        throw_if_stopped(stop);
        shaft_renderer_->set_jitter_frame(settings_.slices.frame);  // one frame's jitter for every pass
        shaft_renderer_->render(camera, settings_.shafts, stats ? &st.scene : nullptr);
        throw_if_stopped(stop);
        const SceneUnderlay under{shaft_renderer_->color_texture(), shaft_renderer_->distance_texture(), &*scene_};
        image = cloud_renderer_->render(camera, cloud_lights(), settings_.slices, &under, stats ? &st.clouds : nullptr, depths);
      } catch (...) {
        shaft_renderer_->set_cloud_shadow(nullptr);  // the map dies here
        throw;
      }
      shaft_renderer_->set_cloud_shadow(nullptr);
      std::snprintf(buf, sizeof buf, "scene %.0f ms (%s), clouds: light %.0f ms, slices %.0f ms, composite %.0f ms",
                    st.scene.total_ms, to_string(settings_.shafts).c_str(), st.clouds.light_ms, st.clouds.slices_ms,
                    st.clouds.composite_ms);
      // The cloud renderer described the frame (scene, camera, clouds, the lights it drew, its
      // slicing); the method is the whole pipeline's.
      image.metadata["method"] = "slices over " + to_string(settings_.shafts);
    } else {
      image = cloud_renderer_->render(camera, cloud_lights(), settings_.slices, nullptr, stats ? &st.clouds : nullptr);
      std::snprintf(buf, sizeof buf, "clouds: light %.0f ms, slices %.0f ms", st.clouds.light_ms, st.clouds.slices_ms);
    }
    st.summary = buf;
    if (settings_.slices.multiple.method == MultipleScatteringMethod::LightVolume) {
      image.metadata["light_volume"] = light_volume_description_;
      char lv[96];
      std::snprintf(lv, sizeof lv, ", light volume %s", st.light_volume_rebuilt ? "" : "reused");
      st.summary += lv;
      if (st.light_volume_rebuilt) {
        std::snprintf(lv, sizeof lv, "built in %.0f ms (CPU)", st.light_volume_build_ms);
        st.summary += lv;
      }
    }
    const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    st.device = renderer ? renderer : "OpenGL";
  }
  image.metadata["device"] = st.device;
  if (stats) *stats = st;
  return image;
}

}  // namespace nimbus::render
