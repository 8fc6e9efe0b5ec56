// The path tracer's medium machinery, shared by the tracer (cloud_path_tracer.cpp) and the
// light-volume photon tracer (light_volume_builder.cpp): a per-stream RNG, each cloud's 8^3 brick
// majorants met by a 3D DDA, delta tracking (Woodcock et al. 1965), ratio tracking (Novak et al.
// 2014) and the sampling of a phase of Henyey-Greenstein lobes. Internal to render/reference.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "nimbus/base/splitmix64.hpp"
#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/cloud_volume.hpp"
#include "grid_walk.hpp"

namespace nimbus::render::traced {

// splitmix64 (Steele, Lea & Flood 2014) as a stream: one per pixel, so an image is the same
// whatever order the threads take the pixels in.
class PathRng {
 public:
  PathRng(uint64_t seed, uint64_t stream) : g_{seed * 0x9E3779B97F4A7C15ULL ^ (stream + 1) * 0xD1B54A32D192ED03ULL} {
    g_.next();
  }
  double uniform() { return g_.uniform(); }  // [0, 1)

 private:
  SplitMix64 g_;
};

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kBrick = 8;  // voxels per brick side: an OpenVDB leaf node

// One cloud as the tracer sees it: its box-local index space and its brick majorants.
struct TracedCloud {
  const CloudVolume* cloud = nullptr;
  glm::dvec3 shift{0.0};  // box origin
  int nb[3] = {0, 0, 0};  // bricks per axis over u = local + 1 in [0, size + 1)
  std::vector<double> majorant;  // per brick: extinction per metre bounding every point inside

  explicit TracedCloud(const CloudVolume& c) : cloud(&c) {
    const volume::DenseBox& b = c.box;
    shift = glm::dvec3(b.origin[0], b.origin[1], b.origin[2]);
    for (int a = 0; a < 3; ++a) nb[a] = static_cast<int>((b.size[a] + 1 + kBrick - 1) / kBrick);
    std::vector<float> max_density(static_cast<std::size_t>(nb[0]) * nb[1] * nb[2], 0.0f);
    const bool next = !c.next_box.values.empty();
    // A point of brick k (u in [8k, 8k + 8), local x = u - 1) reads voxels floor(x) and floor(x) + 1,
    // that is local voxels 8k - 1 .. 8k + 7: voxel i lies in bricks (i - 7) / 8 .. (i + 1) / 8.
    // (ceil((i - 7) / 8) is i / 8 for every i >= 0.)
    auto bricks_of = [](int64_t i, int& lo, int& hi) {
      lo = static_cast<int>(i / kBrick);
      hi = static_cast<int>((i + 1) / kBrick);
    };
    std::size_t n = 0;
    for (int64_t k = 0; k < b.size[2]; ++k)
      for (int64_t j = 0; j < b.size[1]; ++j)
        for (int64_t i = 0; i < b.size[0]; ++i, ++n) {
          const float v = std::max(b.values[n], next ? c.next_box.values[n] : 0.0f);
          if (!(v > 0.0f)) continue;
          int i0, i1, j0, j1, k0, k1;
          bricks_of(i, i0, i1);
          bricks_of(j, j0, j1);
          bricks_of(k, k0, k1);
          for (int bk = k0; bk <= std::min(k1, nb[2] - 1); ++bk)
            for (int bj = j0; bj <= std::min(j1, nb[1] - 1); ++bj)
              for (int bi = i0; bi <= std::min(i1, nb[0] - 1); ++bi) {
                float& m = max_density[static_cast<std::size_t>(bi + nb[0] * (bj + nb[1] * bk))];
                m = std::max(m, v);
              }
        }
    majorant.resize(max_density.size());
    // A little above the bound: trilinear weights sum to 1 only up to rounding.
    for (std::size_t q = 0; q < max_density.size(); ++q)
      majorant[q] = max_density[q] > 0.0f ? c.optics.extinction_per_m * max_density[q] * (1.0 + 1e-9) : 0.0;
  }

  // Visits the bricks a world ray crosses between t0 and t1 (world metres along unit dir), in
  // order: f(s0, s1, majorant, local origin, local dir) returns false to stop.
  template <typename F>
  void march(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1, F f) const {
    const glm::dvec3 lo = glm::dvec3(cloud->world_to_index * glm::dvec4(o, 1.0)) - shift;
    const glm::dvec3 ld = glm::dvec3(cloud->world_to_index * glm::dvec4(d, 0.0));
    // u = local + 1: bricks of kBrick from 0, walked in bricks (u / kBrick, exact).
    const glm::dvec3 ub = (lo + 1.0) / static_cast<double>(kBrick), udb = ld / static_cast<double>(kBrick);
    walk_cells(ub, udb, nb, t0, t1, [&](const glm::ivec3& b, double s0, double s1) {
      return f(s0, s1, majorant[static_cast<std::size_t>(b[0] + nb[0] * (b[1] + nb[1] * b[2]))], lo, ld);
    });
  }

  double sigma_t(const glm::dvec3& lo, const glm::dvec3& ld, double t) const {
    return cloud->optics.extinction_per_m * sample_density_local(*cloud, lo + t * ld);
  }

  // Delta tracking: the first real collision in (t0, t1), or +inf.
  double free_flight(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1, PathRng& rng) const {
    double hit = kInf;
    march(o, d, t0, t1, [&](double s0, double s1, double m, const glm::dvec3& lo, const glm::dvec3& ld) {
      if (m <= 0.0) return true;
      double t = s0;
      while (true) {
        t -= std::log(1.0 - rng.uniform()) / m;
        if (t >= s1) return true;  // memoryless: the next brick starts afresh
        if (rng.uniform() * m < sigma_t(lo, ld, t)) {
          hit = t;
          return false;
        }
      }
    });
    return hit;
  }

  // Ratio tracking: an unbiased estimate of the transmittance over (t0, t1).
  double transmittance(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1, PathRng& rng) const {
    double T = 1.0;
    march(o, d, t0, t1, [&](double s0, double s1, double m, const glm::dvec3& lo, const glm::dvec3& ld) {
      if (m <= 0.0) return true;
      double t = s0;
      while (true) {
        t -= std::log(1.0 - rng.uniform()) / m;
        if (t >= s1) return true;
        T *= 1.0 - sigma_t(lo, ld, t) / m;
        if (T < 1e-3) {  // Russian roulette on the estimate: unbiased, and bounded work
          if (rng.uniform() < 0.5) {
            T = 0.0;
            return false;
          }
          T *= 2.0;
        }
      }
    });
    return T;
  }
};

// Russian roulette on a path's throughput (pbrt-v4's rule): the path survives with probability
// q = min(1, its largest channel) and carries weight / q, so a survivor's weight never exceeds
// max(1, its weight before). Unbiased. A cap q <= 0.95, as before, raised the weight of every
// survivor by albedo / 0.95 = 1.04 a bounce: the rare photon that diffused 200 bounces through a
// dense tower came out weighing thousands (measured: cells of the congestus light volume at
// 20-60x their neighbours, and the path tracer's fireflies there).
inline bool survives_roulette(glm::dvec3& weight, PathRng& rng) {
  const double q = std::min(1.0, std::max({weight.x, weight.y, weight.z}));
  if (!(q > 0.0) || rng.uniform() >= q) return false;
  weight /= q;
  return true;
}

struct Collision {
  double t = kInf;
  int medium = -1;
};

// The first real collision among every cloud: each cloud's own free flight, the nearest wins
// (superposed media: T = prod T_j, so the first collision is the minimum of independent ones).
inline Collision collide(const std::vector<TracedCloud>& media, const glm::dvec3& o, const glm::dvec3& d, PathRng& rng) {
  Collision c;
  for (std::size_t j = 0; j < media.size(); ++j) {
    const double t = media[j].free_flight(o, d, 0.0, c.t, rng);
    if (t < c.t) {
      c.t = t;
      c.medium = static_cast<int>(j);
    }
  }
  return c;
}

inline double transmittance(const std::vector<TracedCloud>& media, const glm::dvec3& o, const glm::dvec3& d, PathRng& rng) {
  double T = 1.0;
  for (const TracedCloud& m : media) {
    T *= m.transmittance(o, d, 0.0, kInf, rng);
    if (T == 0.0) break;
  }
  return T;
}

// Henyey-Greenstein sampling of cos(theta) about the forward direction (theta = 0 forward).
inline double sample_hg_cos(double g, double u) {
  if (std::abs(g) < 1e-4) return 2.0 * u - 1.0;
  const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
  return std::clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
}

// A direction at cos_theta from `w` with a uniform azimuth.
inline glm::dvec3 rotate_about(const glm::dvec3& w, double cos_theta, double u) {
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  const double phi = 2.0 * M_PI * u;
  const glm::dvec3 a = std::abs(w.x) > 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  const glm::dvec3 t = glm::normalize(glm::cross(a, w));
  const glm::dvec3 b = glm::cross(w, t);
  return glm::normalize(cos_theta * w + sin_theta * (std::cos(phi) * t + std::sin(phi) * b));
}

// A phase of Henyey-Greenstein lobes sampled in its dual-lobe form: a lobe by its weight, then
// that lobe's HG. The pdf is the phase itself, so the path weight does not change.
inline glm::dvec3 sample_phase(const Phase& phase, const glm::dvec3& w, PathRng& rng) {
  const Phase p = as_dual_lobes(phase);
  const double g = rng.uniform() < p.forward_weight ? p.g : p.g_back;
  return rotate_about(w, sample_hg_cos(g, rng.uniform()), rng.uniform());
}

inline std::vector<TracedCloud> media_of(const std::vector<CloudVolume>& clouds) {
  std::vector<TracedCloud> media;
  media.reserve(clouds.size());
  for (const CloudVolume& c : clouds) {
    validate(c.optics);
    if (c.box.values.size() != static_cast<std::size_t>(c.box.size[0] * c.box.size[1] * c.box.size[2]))
      throw std::invalid_argument("path tracer cloud '" + c.name + "': box size does not match its values");
    if (!c.next_box.values.empty() && c.next_box.values.size() != c.box.values.size())
      throw std::invalid_argument("path tracer cloud '" + c.name + "': its next keyframe must lie on the same box");
    media.emplace_back(c);
  }
  return media;
}

}  // namespace nimbus::render::traced
