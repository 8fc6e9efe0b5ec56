// Validation, phase and parsing of the cloud optics (cloud_optics.hpp).
#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/base/input_limits.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "nimbus/base/validate.hpp"
#include "nimbus/render/core/phase.hpp"
#include "nimbus/render/core/render_settings.hpp"

namespace nimbus::render {
namespace {

void validate_g(double g, const char* field) {
  require(std::isfinite(g) && g > -1.0 && g < 1.0, std::string(field) + " must be in (-1, 1)");
}

}  // namespace

void validate(const CloudOptics& o) {
  // Beyond 1e12 per metre (as the CLI's flags) the slicer's optical depths overflow its floats.
  require(in_range(setting(Setting::CloudExtinction), o.extinction_per_m),
          "cloud extinction_per_m must be in " + range_text(setting(Setting::CloudExtinction)));
  for (int c = 0; c < 3; ++c)
    require(std::isfinite(o.albedo[c]) && o.albedo[c] >= 0.0 && o.albedo[c] <= 1.0,
            "cloud albedo must be in [0, 1] per channel");
  validate_g(o.phase.g_forward, "cloud phase g_forward");
  validate_g(o.phase.g_back, "cloud phase g_back");
  require(std::isfinite(o.phase.forward_weight) && o.phase.forward_weight >= 0.0 && o.phase.forward_weight <= 1.0,
          "cloud phase forward_weight must be in [0, 1]");
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

double cloud_phase_value(const DualLobePhase& p, double cos_theta) {
  const Phase f{PhaseKind::HenyeyGreenstein, p.g_forward};
  const Phase b{PhaseKind::HenyeyGreenstein, p.g_back};
  return p.forward_weight * phase_value(f, cos_theta) + (1.0 - p.forward_weight) * phase_value(b, cos_theta);
}

DualLobePhase parse_cloud_phase(const std::string& text) {
  DualLobePhase p;
  if (text.rfind("dual:", 0) != 0) {
    // "isotropic" and "hg:G" are the medium's own phase names (phase.hpp): one parser for both,
    // whose errors name the text.
    if (text != "isotropic" && text.rfind("hg:", 0) != 0)
      throw std::invalid_argument("cloud phase '" + echo(text) + "': expected isotropic, hg:G or dual:GF,GB,W");
    p.g_forward = parse_phase(text).g;
    return p;
  }
  std::stringstream ss(text.substr(5));
  double part[3] = {0.0, 0.0, 0.0};
  int n = 0;
  for (std::string item; std::getline(ss, item, ',');) {
    if (n == 3) throw std::invalid_argument("cloud phase '" + echo(text) + "': expected dual:GF,GB,W");
    const std::optional<double> v = parse_double(item);
    if (!v) throw std::invalid_argument("cloud phase '" + echo(text) + "': '" + echo(item) + "' is not a number");
    part[n++] = *v;
  }
  if (n != 3) throw std::invalid_argument("cloud phase '" + echo(text) + "': expected dual:GF,GB,W");
  p.g_forward = part[0];
  p.g_back = part[1];
  p.forward_weight = part[2];
  try {
    CloudOptics o;
    o.phase = p;
    validate(o);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("cloud phase '" + echo(text) + "': " + e.what());
  }
  return p;
}

std::string to_string(const DualLobePhase& p) {
  std::ostringstream s;
  if (p.forward_weight == 1.0 && p.g_forward == 0.0) return "isotropic";
  if (p.forward_weight == 1.0) {
    s << "hg:" << p.g_forward;
  } else {
    s << "dual:" << p.g_forward << "," << p.g_back << "," << p.forward_weight;
  }
  return s.str();
}

}  // namespace nimbus::render
