// The animated sky through the frame pipeline: a view state (render/core/view_state.hpp) in, a
// frame out. It keeps the sky's keyframes (made on a background thread), uploads a keyframe pair
// when the evolution clock crosses into it, and otherwise only moves the clouds (wind drift,
// keyframe blend) and the sun. The light volume (the default multiple scattering) is built per
// keyframe in the background (keyframe_light_volumes.hpp), mixed as the density blends
// (mix_light_volumes) and shifted with the wind; while a new sun's or pair's volumes are made,
// the last one stays on screen, and before the first, the octaves stand in. `nimbus view`, its scripted runs, `nimbus render --view-state` and
// `nimbus bench view` all draw through it, so a screenshot and an offline render of the same
// state are the same frame.
#pragma once
#include <cmath>
#include <utility>
#include <cstdint>
#include <memory>
#include <optional>

#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/core/image.hpp"
#include "nimbus/render/sky/progressive_frame.hpp"
#include "nimbus/render/sky/sky_keyframes.hpp"
#include "nimbus/render/sky/view_state.hpp"
#include "nimbus/render/frame/frame_renderer.hpp"
#include "nimbus/render/sky/keyframe_light_volumes.hpp"

namespace nimbus::render {

// What the adaptive quality may lower for one frame; the state's own values are full quality.
struct FrameQuality {
  double render_scale = 1.0;  // (0, 1], times the state's render_scale
  int slices = 0;             // 0: the state's
  // A still view's progressive sample (progressive_sample(i), progressive_frame.hpp): its
  // sub-pixel offset and jitter. {} is the plain frame.
  ProgressiveSample sample;
  int light_res = 0;          // the light buffer's side: 0, the state's; else [16, 4096]
};

// The pixels a frame of width x height is rendered at under a render scale: each side rounded,
// zero when below half a pixel (callers refuse that rather than draw one pixel).
inline std::pair<int, int> scaled_frame_size(int width, int height, double scale) {
  return {static_cast<int>(std::lround(width * scale)), static_cast<int>(std::lround(height * scale))};
}

struct SkyFrameInfo {
  int64_t keyframe = 0;           // the pair (keyframe, keyframe + 1) drawn
  double blend = 0.0;             // towards keyframe + 1
  double evolution_time_s = 0.0;  // the evolution time drawn: the state's, or earlier while its keyframes are made
  bool waited = false;            // the keyframes were not ready and the evolution was held
  bool uploaded = false;          // a new pair was uploaded for this frame
  int width = 0, height = 0;      // pixels rendered
  int slices = 0;
  double upload_ms = 0.0;         // CPU time making and uploading the pair
  // Multiple scattering drawn: "light volume" (this frame's pair and sun), "light volume (preview)"
  // (this sun's quick volume of fewer photons, while its full one is built), "light volume
  // (stale)" (an earlier one's, while this one's is built), or "octaves" (asked for, or standing in
  // before the first light volume is made).
  std::string multiple = "octaves";
  double light_volume_ms = 0.0;   // CPU time mixing and uploading a light volume this frame
  glm::dvec3 cloud_offset_m{0.0};  // the wind's drift of every cloud at this sky time, render space
  Camera camera;                  // the camera drawn (its size and pixel offset)
};

// The camera a state describes, at a size (near and far planes fitted to the clouds).
Camera state_camera(const ViewState& state, int width, int height, const std::vector<CloudVolume>& clouds);

// The frame a state describes (frame_description.hpp), at a quality: its scene under the
// daylight's sun (set_up_sun with SunColour::Daylight: the viewer's clock lights every scene, and
// clouds alone, by the daylight), the optics with the daylight's ambient, the camera at its default
// size (render() sizes it) and the renderer's settings.
FrameDescription frame_description(const ViewState& state, const FrameQuality& quality);

class SkyRenderer {
 public:
  // Needs a current GL 4.5 context. Starts making the state's keyframes. Throws
  // std::invalid_argument for a bad state.
  explicit SkyRenderer(const ViewState& state);
  // The same, taking over another renderer's keyframes when they hold the same sky (a shader
  // reload builds a new renderer and keeps what was generated).
  SkyRenderer(const ViewState& state, std::shared_ptr<SkyKeyframes> keyframes);
  ~SkyRenderer();

  // A frame of `state` at width x height (before the render scale). wait: block until the
  // state's keyframes are made, so the frame is exactly the state (scripts, offline renders);
  // otherwise draw the nearest made evolution time at or before the state's (never waiting).
  // Applies a changed sky (new keyframes), sun, optics and settings first. Throws
  // std::runtime_error when keyframe generation failed, std::invalid_argument for a bad state.
  // `depths`: what each pixel shows and how far, for the temporal frame (FrameRenderer::render).
  Image render(const ViewState& state, int width, int height, const FrameQuality& quality, bool wait,
               FrameStats* stats = nullptr, SkyFrameInfo* info = nullptr, PixelDepths* depths = nullptr);

  // The clouds as last drawn (moved); empty before the first frame.
  const std::vector<CloudVolume>& clouds() const;
  SkyKeyframes& keyframes() { return *keyframes_; }
  // The scene drawn under the clouds (none for "none").
  const std::optional<Scene>& scene() const { return frame_->scene(); }
  // The light volumes' builder (null before the light-volume method was first asked for).
  const KeyframeLightVolumes* light_volumes() const { return volumes_.get(); }
  std::shared_ptr<SkyKeyframes> shared_keyframes() const { return keyframes_; }

 private:
  void apply(const ViewState& state, const FrameQuality& quality);
  // Chooses, mixes and uploads this frame's light volume; false when there is none to draw yet.
  bool update_light_volume(const ViewState& state, int64_t k, double blend, bool wait);

  std::shared_ptr<SkyKeyframes> keyframes_;  // the state's sky
  std::shared_ptr<SkyKeyframes> drawn_;      // whose pair is uploaded: an edited sky's old clouds
                                             // stay on screen until the new ones are made
  std::unique_ptr<FrameRenderer> frame_;
  std::optional<ViewState> applied_;  // what the renderer was last set up for
  std::optional<int64_t> pair_;       // the keyframe pair uploaded (of drawn_)
  double drawn_blend_ = 0.0;
  // The light volume: built per keyframe of keyframes_; the one uploaded is keyframe shown_k_'s
  // mixed towards shown_k_ + 1's by shown_blend_, under shown_light_, its corner (no wind) shown_min_.
  std::unique_ptr<KeyframeLightVolumes> volumes_;
  std::shared_ptr<const LightVolume> shown_a_, shown_b_;
  std::shared_ptr<const LightVolume> b_on_a_;  // shown_b_ read on shown_a_'s grid
  double shown_blend_ = -1.0;
  glm::dvec3 shown_min_{0.0};
  bool shown_current_ = false;
  // The light whose quick volume (a kPreviewShare-th of its photons) has been shown, and whether
  // the volume on screen is that one.
  std::optional<KeyframeLight> preview_of_;
  bool shown_preview_ = false;
  static constexpr std::int64_t kPreviewShare = 8, kPreviewMinPhotons = 1024;
  // Uploads keyframe k's volume a mixed towards k + 1's b by `blend`, unless the same pair is on
  // screen within `step` of that blend.
  void show_light_volume(const std::shared_ptr<const LightVolume>& a, const std::shared_ptr<const LightVolume>& b,
                         double blend, double step);
};

}  // namespace nimbus::render
