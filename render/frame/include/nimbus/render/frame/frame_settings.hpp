// How the frame pipeline renders: the method (the half-angle slicer, or a CPU reference), each
// method's settings, the scene's light-shaft method and its shadow maps, the clouds' texture format.
// No GL type: a program or a view state holds it without the GL layer.
#pragma once
#include "nimbus/render/core/cloud_slice_settings.hpp"
#include "nimbus/render/core/cloud_method.hpp"
#include "nimbus/render/core/render_settings.hpp"
#include "nimbus/render/media/shaft_method.hpp"
#include "nimbus/render/core/shaft_settings.hpp"
#include "nimbus/render/core/volume_format.hpp"
#include "nimbus/render/reference/cloud_path_tracer.hpp"
#include "nimbus/render/reference/cloud_reference.hpp"

namespace nimbus::render {

struct FrameSettings {
  CloudMethod method = CloudMethod::Slices;
  CloudSliceSettings slices;         // Slices
  CloudReferenceSettings reference;  // Reference (its progress callback too)
  PathTracerSettings path_tracer;    // PathTrace (its progress callback too)
  // The scene under the clouds: a GPU method (not Reference), and its shadow maps.
  ShaftMethod shafts{ShaftMethod::Kind::RayMarch, 48, {}, Jitter::BlueNoise};
  ShaftSettings shaft_settings;
  // Texels per side of the clouds' shadow on the scene (its range: render_settings.hpp).
  int cloud_shadow_res = int(setting(Setting::CloudShadowRes).still_default);
  VolumeFormat volume_format = VolumeFormat::Half;  // the clouds' density textures
};

// Throws std::invalid_argument naming the field (slices, reference, shafts, cloud_shadow_res,
// volume_format).
void validate(const FrameSettings& settings);

}  // namespace nimbus::render
