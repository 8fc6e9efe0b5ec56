// The animated sky through the frame pipeline (sky_renderer.hpp).
#include "nimbus/render/frame/sky_renderer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "nimbus/render/core/cloud_framing.hpp"
#include "nimbus/render/scene/daylight.hpp"
#include "nimbus/render/scene/sun_setup.hpp"
#include "nimbus/render/scene/scene.hpp"
#include "nimbus/render/media/shaft_method.hpp"

namespace nimbus::render {
namespace {

FrameSettings frame_settings(const ViewState& s, const FrameQuality& q) {
  FrameSettings fs;
  fs.method = CloudMethod::Slices;
  fs.slices = s.slices;
  if (q.slices > 0) fs.slices.slices = q.slices;
  if (q.light_res > 0) fs.slices.light_res = q.light_res;
  // A fixed blue-noise pattern per sample: no banding, and no flicker while paused; a still
  // view's samples shift it, and their mean loses the grain (progressive_frame.hpp).
  fs.slices.frame = q.sample.jitter_frame;
  fs.slices.ambient = true;
  fs.shafts = s.shafts;
  fs.cloud_shadow_res = s.cloud_shadow_res;
  return fs;
}

// The state's sun (sun_setup.hpp): the viewer's clock lights every scene, and the clouds alone,
// by the daylight; the sky scene's physical sky follows it.
SunSetup state_sun(const ViewState& s, const Scene* scene) {
  return set_up_sun(scene, sun_direction(s.sky.sun_elevation_deg, s.sky.sun_azimuth_deg), SunColour::Daylight);
}

// The state's optics, with the daylight's ambient whatever the scene.
CloudOptics state_optics(const ViewState& s) {
  CloudOptics o = s.optics;
  o.ambient_radiance = *state_sun(s, nullptr).ambient_w_sr_m2;  // the daylight's, whatever the scene
  return o;
}

// What the keyframes hold: the sky without its wind and sun.
nlohmann::json clouds_of(const volume::Sky& sky) {
  nlohmann::json j = volume::sky_to_json(sky);
  j.erase("wind");
  j.erase("sun");
  return j;
}

}  // namespace

Camera state_camera(const ViewState& state, int width, int height, const std::vector<CloudVolume>& clouds) {
  Camera c = state.camera;
  c.width = width;
  c.height = height;
  c.near_m = 1.0;
  c.far_m = 40000.0;  // the sky scene's: its sky ends at 20 km
  return fit_far_plane(c, clouds, state.slices.repeat_to_m);
}

FrameDescription frame_description(const ViewState& s, const FrameQuality& q) {
  FrameDescription f;
  if (s.scene != "none") {
    // A preset keeps its lamps; the viewer's clock gives it the daylight's sun (and the sky scene
    // its physical sky).
    f.scene = make_scene(s.scene);
    place_sun(*f.scene, state_sun(s, &*f.scene));
  } else {
    f.lights = {state_sun(s, nullptr).sun};
  }
  f.optics = state_optics(s);
  f.camera = state_camera(s, f.camera.width, f.camera.height, {});
  f.settings = frame_settings(s, q);
  return f;
}

SkyRenderer::SkyRenderer(const ViewState& state) : SkyRenderer(state, nullptr) {}

SkyRenderer::SkyRenderer(const ViewState& state, std::shared_ptr<SkyKeyframes> keyframes) {
  validate(state);
  if (keyframes && clouds_of(keyframes->sky()) == clouds_of(state.sky)) {
    keyframes_ = std::move(keyframes);
  } else {
    keyframes_ = std::make_shared<SkyKeyframes>(state.sky, state_optics(state));
  }
  frame_ = std::make_unique<FrameRenderer>(frame_description(state, FrameQuality{}));
  applied_ = state;
}

SkyRenderer::~SkyRenderer() = default;

const std::vector<CloudVolume>& SkyRenderer::clouds() const {
  static const std::vector<CloudVolume> none;
  return pair_ ? frame_->clouds() : none;
}

void SkyRenderer::apply(const ViewState& s, const FrameQuality& q) {
  validate(s);
  if (!(q.render_scale > 0.0 && q.render_scale <= 1.0)) throw std::invalid_argument("frame quality render_scale: must be in (0, 1]");
  if (q.slices != 0 && (q.slices < 2 || q.slices > 4096)) throw std::invalid_argument("frame quality slices: must be 0 or in [2, 4096]");
  if (q.light_res != 0 && (q.light_res < 16 || q.light_res > 4096))
    throw std::invalid_argument("frame quality light_res: must be 0 or in [16, 4096]");
  const ViewState& a = *applied_;
  // The keyframes hold the clouds only: a new wind or sun needs none.
  if (clouds_of(a.sky) != clouds_of(s.sky)) keyframes_ = std::make_shared<SkyKeyframes>(s.sky, state_optics(s));
  if (a.scene != s.scene) {
    // A new scene: a new pipeline (its programs compile again); the clouds are uploaded anew.
    frame_ = std::make_unique<FrameRenderer>(frame_description(s, q));
    pair_.reset();
    drawn_.reset();
    shown_a_.reset();
    shown_b_.reset();
  } else if (a.sky.sun_elevation_deg != s.sky.sun_elevation_deg || a.sky.sun_azimuth_deg != s.sky.sun_azimuth_deg) {
    frame_->set_sun(state_sun(s, frame_->scene() ? &*frame_->scene() : nullptr));
  }
  frame_->set_optics(state_optics(s));
  frame_->set_settings(frame_settings(s, q));
  applied_ = s;
}

bool SkyRenderer::update_light_volume(const ViewState& s, int64_t k, double blend, bool wait) {
  if (!volumes_ || volumes_->keyframes() != keyframes_) {
    volumes_ = std::make_unique<KeyframeLightVolumes>(keyframes_);
    preview_of_.reset();  // a new sky's volumes start with their previews too
  }
  // The volumes follow the newest sky; while an edited sky's keyframes are made, the old
  // clouds keep the volume last shown.
  shown_current_ = false;
  if (drawn_ != keyframes_) return shown_a_ != nullptr;
  if (const std::string e = volumes_->error(); !e.empty()) throw std::runtime_error(e);
  KeyframeLight light;
  light.direction_to_sun = glm::normalize(state_sun(s, nullptr).sun.direction_to_sun);
  light.extinction_per_m = s.optics.extinction_per_m;
  light.albedo = s.optics.albedo;
  light.phase = s.optics.phase;
  light.settings = s.slices.multiple.light_volume;
  const int direction = s.speed >= 0.0 ? 1 : -1;
  // A new light (the sun dragged in the panel, new optics) gets a quick volume first, of a
  // kPreviewShare-th of the photons for keyframe k alone (drawn for the whole pair), then its
  // full ones: the new sun's light is on screen after one quick build, and the full volumes
  // replace it when made (docs/viewer.md).
  KeyframeLight preview = light;
  preview.settings.photons = std::max<std::int64_t>(kPreviewMinPhotons, light.settings.photons / kPreviewShare);
  shown_preview_ = false;
  if (!wait && preview.settings.photons < light.settings.photons && !(preview_of_ && *preview_of_ == light)) {
    volumes_->request(preview, k, direction, 1);
    const std::shared_ptr<const LightVolume> pa = volumes_->get(preview, k);
    if (!pa) return shown_a_ != nullptr;  // the last one shown, if any, until the preview is made
    show_light_volume(pa, pa, 0.0, 0.0);
    preview_of_ = light;
    shown_preview_ = true;
    return true;
  }
  volumes_->request(light, k, direction);
  std::shared_ptr<const LightVolume> a, b;
  if (wait) {
    keyframes_->wait(k + 2);  // keyframe k + 1's volume is that of the pair (k + 1, k + 2)
    a = volumes_->wait(light, k);
    b = volumes_->wait(light, k + 1);
  } else {
    a = volumes_->get(light, k);
    b = volumes_->get(light, k + 1);
  }
  if (!a) {  // the last one shown, if any, until this one is made: this light's preview, or older
    shown_preview_ = shown_a_ != nullptr && preview_of_ && *preview_of_ == light && shown_a_->photons < light.settings.photons;
    return shown_a_ != nullptr;
  }
  const bool both = b != nullptr;
  if (!both) {
    b = a;  // the pair's first end alone until its second is made
    blend = 0.0;
  }
  // A new mix when the volumes change, or the blend by more than a 64th (exactly, when waiting:
  // the frame must be the state's).
  show_light_volume(a, b, blend, wait ? 0.0 : 1.0 / 64.0);
  preview_of_ = light;
  shown_current_ = both;
  return true;
}

void SkyRenderer::show_light_volume(const std::shared_ptr<const LightVolume>& a, const std::shared_ptr<const LightVolume>& b,
                                    double blend, double step) {
  if (a == shown_a_ && b == shown_b_ && !(std::abs(blend - shown_blend_) > step)) return;
  // Keyframe k + 1's volume read on k's grid once per pair; each new blend is then a lerp.
  if (a != shown_a_ || b != shown_b_) b_on_a_ = std::make_shared<const LightVolume>(mix_light_volumes(*a, *b, 1.0));
  const LightVolume mixed = mix_light_volumes(*a, *b_on_a_, blend);
  frame_->set_light_volume(mixed);
  shown_a_ = a;
  shown_b_ = b;
  shown_blend_ = blend;
  shown_min_ = mixed.world_min;
}

Image SkyRenderer::render(const ViewState& state, int width, int height, const FrameQuality& quality, bool wait,
                          FrameStats* stats, SkyFrameInfo* info, PixelDepths* depths) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw std::invalid_argument("sky frame size must be in [1, 16384] pixels per side");
  apply(state, quality);
  SkyKeyframes& kf = *keyframes_;
  if (const std::string e = kf.error(); !e.empty()) throw std::runtime_error(e);
  SkyFrameInfo fi;
  int64_t k = kf.keyframe_at(state.evolution_time_s);
  double blend = kf.blend_at(state.evolution_time_s);
  kf.request(k, state.speed >= 0.0 ? 1 : -1);
  // Nothing drawn yet: the first pair must be waited for whatever the caller asked.
  if (wait || !pair_) {
    kf.wait(k);
    kf.wait(k + 1);
  }
  if (kf.ready(k) && kf.ready(k + 1)) {
    if (drawn_ != keyframes_ || !pair_ || *pair_ != k) {
      const auto start = std::chrono::steady_clock::now();
      frame_->set_clouds(kf.pair(k));
      frame_->set_optics(state_optics(state));
      drawn_ = keyframes_;
      pair_ = k;
      fi.uploaded = true;
      fi.upload_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
  } else {
    // Hold the evolution where the drawn pair can show it (never a jump back): at its nearer
    // end, or, while an edited sky's keyframes are made, where the old sky was.
    fi.waited = true;
    if (drawn_ == keyframes_) blend = k > *pair_ ? 1.0 : 0.0;
    else blend = drawn_blend_;
    k = *pair_;
  }
  drawn_blend_ = blend;
  const std::vector<CloudMotion> motion = drawn_->motion(state.sky_time_s, state.sky.wind_m_s, blend);
  frame_->set_motion(motion);
  if (state.slices.multiple.method == MultipleScatteringMethod::LightVolume) {
    const auto start = std::chrono::steady_clock::now();
    if (update_light_volume(state, k, blend, wait)) {
      frame_->move_light_volume(shown_min_ + (motion.empty() ? glm::dvec3(0.0) : motion.front().offset_m));
      fi.multiple = shown_current_ ? "light volume" : shown_preview_ ? "light volume (preview)" : "light volume (stale)";
    } else {
      FrameSettings fs = frame_->settings();  // the octaves stand in until the first volume is made
      fs.slices.multiple.method = MultipleScatteringMethod::Octaves;
      frame_->set_settings(fs);
    }
    fi.light_volume_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  const double scale = std::clamp(state.render_scale * quality.render_scale, 0.01, 1.0);
  const auto [sw, sh] = scaled_frame_size(width, height, scale);
  const int w = std::max(1, sw), h = std::max(1, sh);
  Camera camera = state_camera(state, w, h, frame_->clouds());
  camera.pixel_offset = quality.sample.pixel_offset;
  Image image = frame_->render(camera, stats, depths);
  fi.camera = camera;
  fi.cloud_offset_m = motion.empty() ? glm::dvec3(0.0) : motion.front().offset_m;
  fi.keyframe = k;
  fi.blend = blend;
  fi.evolution_time_s = fi.waited ? (static_cast<double>(k) + blend) * drawn_->interval_s() : state.evolution_time_s;
  fi.width = w;
  fi.height = h;
  fi.slices = frame_->settings().slices.slices;
  ViewState drawn = state;
  drawn.evolution_time_s = fi.evolution_time_s;
  image.metadata["view_state"] = view_state_to_json(drawn).dump();
  image.metadata["sky_time_s"] = std::to_string(state.sky_time_s);
  image.metadata["evolution_time_s"] = std::to_string(fi.evolution_time_s);
  image.metadata["keyframes"] = std::to_string(k) + ", " + std::to_string(k + 1) + " blend " + std::to_string(blend);
  if (info) *info = fi;
  return image;
}

}  // namespace nimbus::render
