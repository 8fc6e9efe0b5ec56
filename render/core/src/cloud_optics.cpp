// Validation, phase and parsing of the cloud optics (cloud_optics.hpp).
#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/base/input_limits.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "nimbus/base/validate.hpp"
#include "nimbus/render/core/phase.hpp"
#include "nimbus/render/core/render_settings.hpp"

namespace nimbus::render {
void validate(const CloudOptics& o) {
  // Beyond 1e12 per metre (as the CLI's flags) the slicer's optical depths overflow its floats.
  require(in_range(setting(Setting::CloudExtinction), o.extinction_per_m),
          "cloud extinction_per_m must be in " + range_text(setting(Setting::CloudExtinction)));
  for (int c = 0; c < 3; ++c)
    require(std::isfinite(o.albedo[c]) && o.albedo[c] >= 0.0 && o.albedo[c] <= 1.0,
            "cloud albedo must be in [0, 1] per channel");
  validate(o.phase, "cloud phase");
  as_dual_lobes(o.phase);  // Henyey-Greenstein lobes: what the slicer, the light volume and the path tracer take
  for (int c = 0; c < 3; ++c)
    require(std::isfinite(o.ambient_radiance[c]) && o.ambient_radiance[c] >= 0.0 && o.ambient_radiance[c] <= 1e12,
            "cloud ambient_radiance must be in [0, 1e12] per channel");
}

void validate(const MultipleScattering& m) {
  check_setting(Setting::Multiple, m.octaves, "multiple-scattering octaves");
  check_setting(Setting::MsOcclusion, m.occlusion, "multiple-scattering occlusion");
  check_setting(Setting::MsContribution, m.contribution, "multiple-scattering contribution");
  check_setting(Setting::MsEccentricity, m.eccentricity, "multiple-scattering eccentricity");
  require(m.method == MultipleScatteringMethod::Octaves || m.method == MultipleScatteringMethod::LightVolume,
          "multiple-scattering method is not one of octaves, light-volume");
  validate(m.light_volume);
}

void validate(const LightVolumeSettings& s) {
  check_setting(Setting::MsGrid, s.resolution, "light volume resolution");
  check_setting(Setting::MsPhotons, double(s.photons), "light volume photons");
  require(std::isfinite(s.photons_per_cell) && s.photons_per_cell >= 0.0 && s.photons_per_cell <= 1e9,
          "light volume photons per cell must be in [0, 1e9] (0: the resolution exactly), got " +
              std::to_string(s.photons_per_cell));
  check_setting(Setting::MsLobes, s.lobe_orders, "light volume lobe orders");
  check_setting(Setting::MsDiffusionDepth, s.diffusion_depth, "light volume diffusion depth (0: off)");
  check_setting(Setting::MsSimilarityDepth, s.similarity_depth, "light volume similarity depth (0: off)");
  require(s.threads >= 0, "light volume threads must be >= 0 (0 = all cores)");
}

MultipleScatteringMethod parse_multiple_scattering_method(const std::string& text) {
  if (text == "octaves") return MultipleScatteringMethod::Octaves;
  if (text == "light-volume") return MultipleScatteringMethod::LightVolume;
  throw std::invalid_argument("multiple-scattering method '" + echo(text) + "': expected octaves or light-volume");
}

std::string to_string(MultipleScatteringMethod m) {
  switch (m) {
    case MultipleScatteringMethod::Octaves: return "octaves";
    case MultipleScatteringMethod::LightVolume: return "light-volume";
  }
  return "unknown";
}

glm::vec3 cloud_phase_lobes(const Phase& phase) {
  const Phase p = as_dual_lobes(phase);
  return glm::vec3(static_cast<float>(p.g), static_cast<float>(p.g_back), static_cast<float>(p.forward_weight));
}

Phase parse_cloud_phase(const std::string& text) {
  const Phase p = parse_phase(text);
  try {
    as_dual_lobes(p);
  } catch (const std::invalid_argument&) {
    throw std::invalid_argument("cloud phase '" + echo(text) +
                                "': clouds take Henyey-Greenstein lobes: isotropic, hg:G or dual:GF,GB,W");
  }
  return p;
}

}  // namespace nimbus::render
