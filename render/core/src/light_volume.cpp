// Reading the light volume on the CPU (light_volume.hpp): what the slice shader does with its
// 3D textures, in double precision.
#include "nimbus/render/core/light_volume.hpp"

#include <algorithm>
#include <cmath>

namespace nimbus::render {

void sample_light_volume(const LightVolume& v, const glm::dvec3& world_m, glm::dvec3& fluence, glm::dvec3& flux) {
  fluence = glm::dvec3(0.0);
  flux = glm::dvec3(0.0);
  if (v.cells() == 0 || !(v.cell_m > 0.0)) return;
  // Cell centres at (i + 0.5) cell_m from the corner.
  const glm::dvec3 u = (world_m - v.world_min) / v.cell_m - 0.5;
  int i0[3], i1[3];
  double f[3];
  for (int a = 0; a < 3; ++a) {
    const double x = std::clamp(u[a], 0.0, static_cast<double>(v.size[a] - 1));
    i0[a] = std::min(static_cast<int>(std::floor(x)), v.size[a] - 1);
    i1[a] = std::min(i0[a] + 1, v.size[a] - 1);
    f[a] = x - i0[a];
  }
  for (int c = 0; c < 8; ++c) {
    const int i = (c & 1) ? i1[0] : i0[0], j = (c & 2) ? i1[1] : i0[1], k = (c & 4) ? i1[2] : i0[2];
    const double w = ((c & 1) ? f[0] : 1.0 - f[0]) * ((c & 2) ? f[1] : 1.0 - f[1]) * ((c & 4) ? f[2] : 1.0 - f[2]);
    const std::size_t n = static_cast<std::size_t>(i) + static_cast<std::size_t>(v.size[0]) * (j + static_cast<std::size_t>(v.size[1]) * k);
    fluence += w * glm::dvec3(v.fluence_rgb[3 * n], v.fluence_rgb[3 * n + 1], v.fluence_rgb[3 * n + 2]);
    flux += w * glm::dvec3(v.flux_xyz[3 * n], v.flux_xyz[3 * n + 1], v.flux_xyz[3 * n + 2]);
  }
}

double mean_cosine(const DualLobePhase& p) { return p.forward_weight * p.g_forward + (1.0 - p.forward_weight) * p.g_back; }

glm::dvec3 light_volume_inscatter(const LightVolume& v, const DualLobePhase& phase, const glm::dvec3& world_m,
                                  const glm::dvec3& to_eye) {
  glm::dvec3 phi, F;
  sample_light_volume(v, world_m, phi, F);
  const double mean = (phi.x + phi.y + phi.z) / 3.0;
  const double directional = mean > 0.0 ? 3.0 * mean_cosine(phase) * glm::dot(F, to_eye) / mean : 0.0;
  return glm::max(phi * (1.0 + directional) / (4.0 * M_PI), glm::dvec3(0.0));
}

}  // namespace nimbus::render
