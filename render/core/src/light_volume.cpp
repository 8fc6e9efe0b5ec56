// Reading the light volume on the CPU (light_volume.hpp): what the slice shader does with its
// 3D textures, in double precision.
#include "nimbus/render/core/light_volume.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace nimbus::render {

bool light_volume_is_consistent(const LightVolume& v) {
  const std::size_t n = v.cells();
  if (n == 0 || !(v.cell_m.x > 0.0 && v.cell_m.y > 0.0 && v.cell_m.z > 0.0) || v.fluence_rgb.size() != 3 * n ||
      v.flux_xyz.size() != 3 * n || v.quadrupole.size() != 5 * n || (!v.lobes.empty() && v.lobes.size() != 4 * n) ||
      (!v.gradient.empty() && v.gradient.size() != 4 * n))
    return false;
  for (const std::vector<float>* values : {&v.fluence_rgb, &v.flux_xyz, &v.quadrupole, &v.lobes, &v.gradient})
    for (float x : *values)
      if (!std::isfinite(x)) return false;
  return true;
}

LightVolumeSample sample_light_volume(const LightVolume& v, const glm::dvec3& world_m) {
  LightVolumeSample out;
  if (v.cells() == 0 || !(v.cell_m.x > 0.0 && v.cell_m.y > 0.0 && v.cell_m.z > 0.0)) return out;
  // Cell centres at (i + 0.5) cell_m from the corner.
  const glm::dvec3 u = (world_m - v.world_min) / v.cell_m - 0.5;
  // Eq. MS-4 reads the fits at u inside the grid (beyond it, as at its face).
  const glm::dvec3 uc = glm::clamp(u + 0.5, glm::dvec3(0.0), glm::dvec3(v.size[0], v.size[1], v.size[2]));
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
    if (!v.lobes.empty())
      out.lobes += w * glm::dvec4(v.lobes[4 * n], v.lobes[4 * n + 1], v.lobes[4 * n + 2], v.lobes[4 * n + 3]);
    if (!v.gradient.empty())
      out.fit_offset += w * (v.gradient[4 * n] * uc.x + v.gradient[4 * n + 1] * uc.y + v.gradient[4 * n + 2] * uc.z -
                             v.gradient[4 * n + 3]);
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
  for (const LightVolume* v : {&a, &b})
    if (!light_volume_is_consistent(*v))
      throw std::invalid_argument(std::string("light volume mix: volume ") + (v == &a ? "a" : "b") +
                                  " is empty, its arrays do not match its size or a value is not finite");
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
    // The lobes and the fits (eq. MS-4 is linear in (g, h)); an empty array reads as zeros.
    const std::vector<float> none(4 * a.cells(), 0.0f);
    for (auto member : {&LightVolume::lobes, &LightVolume::gradient}) {
      if ((a.*member).empty() && (b.*member).empty()) continue;
      out.*member = none;
      lerp(out.*member, (a.*member).empty() ? none : a.*member, (b.*member).empty() ? none : b.*member);
    }
    out.build_seconds = a.build_seconds + b.build_seconds;
    return out;
  }
  const bool lobes = !a.lobes.empty() || !b.lobes.empty();
  if (lobes && out.lobes.empty()) out.lobes.assign(4 * a.cells(), 0.0f);
  // b's fits are not carried to another grid: their offset at a's cell centres joins the fluence.
  const bool fits = !a.gradient.empty();
  for (int k = 0; k < a.size[2]; ++k)
    for (int j = 0; j < a.size[1]; ++j)
      for (int i = 0; i < a.size[0]; ++i) {
        const std::size_t n = static_cast<std::size_t>(i) + static_cast<std::size_t>(a.size[0]) * (j + static_cast<std::size_t>(a.size[1]) * k);
        const LightVolumeSample x = sample_light_volume(b, a.world_min + a.cell_m * (glm::dvec3(i, j, k) + 0.5));
        const double mean_b = (x.fluence.x + x.fluence.y + x.fluence.z) / 3.0;
        const double fit_b = mean_b > 0.0 ? std::max(mean_b + x.fit_offset, 0.0) / mean_b : 1.0;
        for (int c = 0; c < 3; ++c) {
          out.fluence_rgb[3 * n + c] = static_cast<float>(s * a.fluence_rgb[3 * n + c] + t * fit_b * x.fluence[c]);
          out.flux_xyz[3 * n + c] = static_cast<float>(s * a.flux_xyz[3 * n + c] + t * x.flux[c]);
        }
        const double q[5] = {x.quadrupole[0][0], x.quadrupole[1][1], x.quadrupole[0][1], x.quadrupole[0][2], x.quadrupole[1][2]};
        for (int e = 0; e < 5; ++e) out.quadrupole[5 * n + e] = static_cast<float>(s * a.quadrupole[5 * n + e] + t * q[e]);
        if (lobes)
          for (int e = 0; e < 4; ++e) out.lobes[4 * n + e] = static_cast<float>(s * out.lobes[4 * n + e] + t * x.lobes[e]);
        if (fits)
          for (int e = 0; e < 4; ++e) out.gradient[4 * n + e] = static_cast<float>(s * out.gradient[4 * n + e]);
      }
  out.build_seconds = a.build_seconds + b.build_seconds;
  return out;
}

double phase_legendre(const Phase& phase, int l) {
  const Phase p = as_dual_lobes(phase);
  return p.forward_weight * std::pow(p.g, l) + (1.0 - p.forward_weight) * std::pow(p.g_back, l);
}

glm::dvec3 light_volume_inscatter(const LightVolume& v, const Phase& cloud_phase, const glm::dvec3& world_m,
                                  const glm::dvec3& to_eye) {
  const Phase phase = as_dual_lobes(cloud_phase);
  const LightVolumeSample s = sample_light_volume(v, world_m);
  const double mean = (s.fluence.x + s.fluence.y + s.fluence.z) / 3.0;
  if (!(mean > 0.0)) return glm::dvec3(0.0);
  // Eq. MS-3: the lobes of orders 1 and 2 about the sun's direction of propagation `sun`, and
  // the harmonics' moments less theirs: phi_h = phi (1 - f_1 - f_2), F_h = F - phi sum f_k mu_k sun,
  // w^T Q_h w = w^T Q w - phi sum f_k mu_k^2 ((w.sun)^2 - 1 / 3).
  const glm::dvec3 sun = v.light_direction;
  const double ws = glm::dot(to_eye, sun);
  const double f[2] = {s.lobes.x, s.lobes.z}, mu[2] = {s.lobes.y, s.lobes.w};
  double harmonic = 1.0, flux_less = 0.0, q_less = 0.0, lobe = 0.0;
  for (int k = 0; k < 2; ++k) {
    if (!(f[k] > 0.0)) continue;
    harmonic -= f[k];
    flux_less += f[k] * mu[k];
    q_less += f[k] * mu[k] * mu[k];
    // HG(g_i) * HG(mu_k) = HG(g_i mu_k): the dual lobe with both g scaled by mu_k.
    lobe += f[k] * 4.0 * M_PI *
            phase_value(dual_lobe_phase(phase.g * mu[k], phase.g_back * mu[k], phase.forward_weight), ws);
  }
  // Eq. MS-1 over the fluence: 1 + 3 p_1 F.w / phi + (15 / 2) p_2 w^T Q w / phi.
  const double directional =
      3.0 * phase_legendre(phase, 1) * (glm::dot(s.flux, to_eye) / mean - flux_less * ws) +
      7.5 * phase_legendre(phase, 2) * (glm::dot(to_eye, s.quadrupole * to_eye) / mean - q_less * (ws * ws - 1.0 / 3.0));
  // Eq. MS-4: the fits' fluence over the interpolated one scales the whole in-scattering.
  const double fit = std::max(mean + s.fit_offset, 0.0) / mean;
  return s.fluence * (fit * (std::max(harmonic + directional, 0.0) + lobe) / (4.0 * M_PI));
}

}  // namespace nimbus::render
