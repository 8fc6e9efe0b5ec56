// How cloud density meets light: extinction and scattering per unit density (world units), a
// phase of Henyey-Greenstein lobes (phase.hpp), an ambient sky term and the multiple-scattering
// approximations; the lights are in light.hpp.
#pragma once
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "nimbus/render/core/light.hpp"
#include "nimbus/render/core/phase.hpp"
#include "nimbus/render/core/render_settings.hpp"

namespace nimbus::render {

// A cloud's look where nothing says otherwise, for nimbus render, the viewer, Python and the
// Blender add-on's material alike: a forward lobe (g 0.7) with a fifth of backward scattering
// (g -0.25), and albedo 0.99 (docs/clouds.md compares the phases).
inline constexpr Phase kCloudPhase = dual_lobe_phase(0.7, -0.25, 0.8);
inline constexpr double kCloudAlbedo = 0.99;

struct CloudOptics {
  double extinction_per_m = setting(Setting::CloudExtinction).still_default;  // sigma_t per unit density, per metre (grey)
  glm::dvec3 albedo{kCloudAlbedo};  // sigma_s / sigma_t per channel, [0, 1] (chromatic allowed)
  Phase phase;  // Henyey-Greenstein lobes only: isotropic, hg or dual (as_dual_lobes)
  // Isotropic sky radiance that lights every point of the cloud unshadowed (W sr^-1 m^-2 per
  // channel); its in-scattered radiance is sigma_s rho L_ambient. 0 switches it off.
  glm::dvec3 ambient_radiance{0.0};
};

// How the light volume (light_volume.hpp) is built: photons from the sun through the clouds
// (render/reference light_volume_builder.hpp), tallied on a grid of cube cells over the clouds' box.
// The ranges, and the defaults of what a front end sets, are the one table's (render_settings.hpp).
struct LightVolumeSettings {
  int resolution = int(setting(Setting::MsGrid).still_default);  // cells along the box's longest axis at least (the others in proportion)
  // Finer cells where the photons allow (light_volume_grid): as narrow as leaves each cell's face
  // about this many photons launched over the box's largest face, but no finer than the clouds'
  // voxels nor 128 along the longest axis. 0 keeps `resolution` exactly. [0, 1e9]
  double photons_per_cell = 1000.0;
  std::int64_t photons = std::int64_t(setting(Setting::MsPhotons).still_default);  // launched from the sun
  std::uint64_t seed = 1;          // the same seed gives the same volume, whatever the threads
  int threads = 0;                 // 0 = all cores
  // Scattering orders 1..lobe_orders kept as Henyey-Greenstein lobes about the sun's direction
  // (light_volume.hpp, eq. MS-3) beside the l <= 2 harmonics; 0 = harmonics alone.
  int lobe_orders = int(setting(Setting::MsLobes).still_default);
  // Linear fits of the fluence inside each cell (light_volume.hpp, eq. MS-4); false: cell means.
  bool fits = true;
  // Deep in the clouds light diffuses: a photon that scatters (after its lobe orders) in a cell
  // at least this many transport mean free paths inside the clouds hands its light to a diffusion
  // solve on the grid (render/reference light_volume_diffusion.hpp, eq. MS-5) instead of walking
  // on. 0: photons carry all the light.
  double diffusion_depth = setting(Setting::MsDiffusionDepth).still_default;
  // Deep in the clouds light forgets its direction: a photon past its lobe orders that scatters in
  // a cell at least this many transport mean free paths inside the clouds flies on in the similar
  // medium (render/reference light_volume_builder.hpp): isotropic scattering with
  // sigma_s' = sigma_s (1 - g), the similarity relation (Wyman, Patterson & Wilson 1989; Zhao et
  // al. 2014), 1 / (1 - albedo g) fewer, longer flights. 0, the default: the true phase everywhere
  // (measured in docs/clouds.md: 1.1-1.3x faster, and the stratus sheet seen from below 2 points
  // worse under HG 0.7).
  double similarity_depth = setting(Setting::MsSimilarityDepth).still_default;
  bool operator==(const LightVolumeSettings&) const = default;
};

// Which multiple-scattering approximation the slicer adds to its exact single scattering.
enum class MultipleScatteringMethod {
  Octaves,      // Unreal-style octaves below (octaves = 0: single scattering)
  LightVolume,  // the per-voxel light volume of photon-traced scattered light (light_volume.hpp)
};

// Unreal-style multiple-scattering approximation (after Wrenninge et al. 2013): octave k = 0..N
// sees the light through extinction scaled by a^k, adds b^k of its radiance, with phase
// asymmetry scaled by c^k. octaves = 0 is single scattering.
struct MultipleScattering {
  MultipleScatteringMethod method = MultipleScatteringMethod::Octaves;
  int octaves = 0;            // extra octaves (Octaves only)
  // a, b, c: the ranges and defaults are the table's (render_settings.hpp)
  double occlusion = setting(Setting::MsOcclusion).still_default;
  double contribution = setting(Setting::MsContribution).still_default;
  double eccentricity = setting(Setting::MsEccentricity).still_default;
  LightVolumeSettings light_volume;  // LightVolume only
};

// "octaves" / "light-volume" <-> the method; parsing throws std::invalid_argument naming the text.
MultipleScatteringMethod parse_multiple_scattering_method(const std::string& text);
std::string to_string(MultipleScatteringMethod method);

// Throw std::invalid_argument naming the field (NaN, infinity, out of range, zero direction).
void validate(const CloudOptics& optics);
void validate(const MultipleScattering& ms);
void validate(const LightVolumeSettings& settings);

// parse_phase for a cloud: "isotropic", "hg:G" or "dual:GF,GB,W"; std::invalid_argument naming
// the text for those malformed and for the fog's other kinds.
Phase parse_cloud_phase(const std::string& text);

// A cloud phase as the shaders take it (lib/cloud_phase.glsl, CloudBlock.phase): its dual-lobe
// form's (g forward, g back, forward weight) in float.
glm::vec3 cloud_phase_lobes(const Phase& phase);

}  // namespace nimbus::render
