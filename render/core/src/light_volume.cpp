// Reading the light volume on the CPU (light_volume.hpp): what the slice shader does with its
// 3D textures, in double precision.
#include "nimbus/render/core/light_volume.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace nimbus::render {

LightVolumeSample sample_light_volume(const LightVolume& v, const glm::dvec3& world_m) {
  LightVolumeSample out;
  if (v.cells() == 0 || !(v.cell_m.x > 0.0 && v.cell_m.y > 0.0 && v.cell_m.z > 0.0)) return out;
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
  double q[5] = {0, 0, 0, 0, 0};
  for (int c = 0; c < 8; ++c) {
    const int i = (c & 1) ? i1[0] : i0[0], j = (c & 2) ? i1[1] : i0[1], k = (c & 4) ? i1[2] : i0[2];
    const double w = ((c & 1) ? f[0] : 1.0 - f[0]) * ((c & 2) ? f[1] : 1.0 - f[1]) * ((c & 4) ? f[2] : 1.0 - f[2]);
    const std::size_t n = static_cast<std::size_t>(i) + static_cast<std::size_t>(v.size[0]) * (j + static_cast<std::size_t>(v.size[1]) * k);
    out.fluence += w * glm::dvec3(v.fluence_rgb[3 * n], v.fluence_rgb[3 * n + 1], v.fluence_rgb[3 * n + 2]);
    out.flux += w * glm::dvec3(v.flux_xyz[3 * n], v.flux_xyz[3 * n + 1], v.flux_xyz[3 * n + 2]);
    if (!v.quadrupole.empty())
      for (int e = 0; e < 5; ++e) q[e] += w * v.quadrupole[5 * n + e];
  }
  // xx, yy, xy, xz, yz; zz = -xx - yy. glm matrices are column-major: m[col][row].
  glm::dmat3& Q = out.quadrupole;
  Q[0][0] = q[0];
  Q[1][1] = q[1];
  Q[2][2] = -q[0] - q[1];
  Q[0][1] = Q[1][0] = q[2];
  Q[0][2] = Q[2][0] = q[3];
  Q[1][2] = Q[2][1] = q[4];
  return out;
}

LightVolume mix_light_volumes(const LightVolume& a, const LightVolume& b, double t) {
  if (!(t >= 0.0 && t <= 1.0)) throw std::invalid_argument("light volume mix: t must be in [0, 1], got " + std::to_string(t));
  for (const LightVolume* v : {&a, &b}) {
    const std::size_t n = v->cells();
    if (n == 0 || !(v->cell_m.x > 0.0 && v->cell_m.y > 0.0 && v->cell_m.z > 0.0) || v->fluence_rgb.size() != 3 * n || v->flux_xyz.size() != 3 * n ||
        v->quadrupole.size() != 5 * n)
      throw std::invalid_argument(std::string("light volume mix: volume ") + (v == &a ? "a" : "b") +
                                  " is empty or its arrays do not match its size");
  }
  LightVolume out = a;
  if (t == 0.0) return out;
  const double s = 1.0 - t;
  if (a.size[0] == b.size[0] && a.size[1] == b.size[1] && a.size[2] == b.size[2] && a.world_min == b.world_min &&
      a.cell_m == b.cell_m) {
    // The same grid: b's cell centres are a's, where the interpolation returns b's cells.
    auto lerp = [&](std::vector<float>& o, const std::vector<float>& x, const std::vector<float>& y) {
      for (std::size_t i = 0; i < o.size(); ++i) o[i] = static_cast<float>(s * x[i] + t * y[i]);
    };
    lerp(out.fluence_rgb, a.fluence_rgb, b.fluence_rgb);
    lerp(out.flux_xyz, a.flux_xyz, b.flux_xyz);
    lerp(out.quadrupole, a.quadrupole, b.quadrupole);
    out.build_seconds = a.build_seconds + b.build_seconds;
    return out;
  }
  for (int k = 0; k < a.size[2]; ++k)
    for (int j = 0; j < a.size[1]; ++j)
      for (int i = 0; i < a.size[0]; ++i) {
        const std::size_t n = static_cast<std::size_t>(i) + static_cast<std::size_t>(a.size[0]) * (j + static_cast<std::size_t>(a.size[1]) * k);
        const LightVolumeSample x = sample_light_volume(b, a.world_min + a.cell_m * (glm::dvec3(i, j, k) + 0.5));
        for (int c = 0; c < 3; ++c) {
          out.fluence_rgb[3 * n + c] = static_cast<float>(s * a.fluence_rgb[3 * n + c] + t * x.fluence[c]);
          out.flux_xyz[3 * n + c] = static_cast<float>(s * a.flux_xyz[3 * n + c] + t * x.flux[c]);
        }
        const double q[5] = {x.quadrupole[0][0], x.quadrupole[1][1], x.quadrupole[0][1], x.quadrupole[0][2], x.quadrupole[1][2]};
        for (int e = 0; e < 5; ++e) out.quadrupole[5 * n + e] = static_cast<float>(s * a.quadrupole[5 * n + e] + t * q[e]);
      }
  out.build_seconds = a.build_seconds + b.build_seconds;
  return out;
}

double phase_legendre(const DualLobePhase& p, int l) {
  return p.forward_weight * std::pow(p.g_forward, l) + (1.0 - p.forward_weight) * std::pow(p.g_back, l);
}

glm::dvec3 light_volume_inscatter(const LightVolume& v, const DualLobePhase& phase, const glm::dvec3& world_m,
                                  const glm::dvec3& to_eye) {
  const LightVolumeSample s = sample_light_volume(v, world_m);
  const double mean = (s.fluence.x + s.fluence.y + s.fluence.z) / 3.0;
  if (!(mean > 0.0)) return glm::dvec3(0.0);
  // Eq. MS-1 over the fluence: 1 + 3 p_1 F.w / phi + (15 / 2) p_2 w^T Q w / phi.
  const double directional = 3.0 * phase_legendre(phase, 1) * glm::dot(s.flux, to_eye) / mean +
                             7.5 * phase_legendre(phase, 2) * glm::dot(to_eye, s.quadrupole * to_eye) / mean;
  return glm::max(s.fluence * (1.0 + directional) / (4.0 * M_PI), glm::dvec3(0.0));
}

}  // namespace nimbus::render
