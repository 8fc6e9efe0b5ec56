// Test support: the plane-parallel slab solved deterministically for a collimated beam, written
// in the tests apart from the code they check (the path tracer, the light volume).
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "nimbus/render/core/cloud_optics.hpp"

namespace nimbus::render::test {

// A deterministic solution of the plane-parallel slab for a collimated beam: discrete ordinates
// (Gauss-Legendre in each hemisphere, the azimuthally averaged phase function normalised so the
// discrete scattering conserves energy), exponential integration across thin layers, and source
// iteration to convergence. Returns the slab's total reflectance and transmittance (the direct
// beam included) for a unit incident flux, and the diffuse light's fluence and flux at each level.
struct SlabSolution {
  double R = 0, T = 0;                 // total reflectance and transmittance (direct beam in T)
  std::vector<double> tau;             // optical depth from the lit face of each level, 0..tau
  std::vector<double> fluence;         // per level: fluence of the diffuse (scattered) light, int I dw
  std::vector<double> flux_down;       // per level: its net flux along the beam's depth axis, int I mu dw
  std::vector<double> second;          // per level: int I (mu^2 - 1/3) dw
};

inline void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.resize(n);
  w.resize(n);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1.0);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-15) break;
    }
    x[i] = 0.5 * (z + 1.0);               // on (0, 1)
    w[i] = 1.0 / ((1.0 - z * z) * dp * dp);  // 2 / (...) on [-1, 1], halved for (0, 1)
  }
}

inline double hg(double g, double c) { return (1.0 - g * g) / (4.0 * M_PI * std::pow(1.0 + g * g - 2.0 * g * c, 1.5)); }

// Azimuthal average (1 / 2 pi) int p(cos Theta) dphi between directions of cosines a and b.
inline double phase_m0(const Phase& p, double a, double b) {
  const int m = 720;
  double s = 0.0;
  for (int k = 0; k < m; ++k) {
    const double phi = M_PI * (k + 0.5) / m;
    const double c = a * b + std::sqrt(std::max(0.0, (1 - a * a) * (1 - b * b))) * std::cos(phi);
    s += p.forward_weight * hg(p.g, c) + (1.0 - p.forward_weight) * hg(p.g_back, c);
  }
  return s / m;
}

inline SlabSolution solve_slab(double tau, double albedo, const Phase& phase, double mu0, int layers = 400) {
  const int n = 24;
  std::vector<double> x, w;
  gauss_legendre(n, x, w);
  // Directions: 0..n-1 downward (cosine +x), n..2n-1 upward (cosine -x).
  std::vector<double> mu(2 * n), wt(2 * n);
  for (int i = 0; i < n; ++i) {
    mu[i] = x[i];
    mu[n + i] = -x[i];
    wt[i] = wt[n + i] = w[i];
  }
  std::vector<double> P(4 * n * n), Pbeam(2 * n);
  for (int i = 0; i < 2 * n; ++i) {
    double row = 0.0;
    for (int j = 0; j < 2 * n; ++j) row += 2.0 * M_PI * wt[j] * (P[i * 2 * n + j] = phase_m0(phase, mu[i], mu[j]));
    for (int j = 0; j < 2 * n; ++j) P[i * 2 * n + j] /= row;  // discrete scattering conserves energy
    Pbeam[i] = phase_m0(phase, mu[i], mu0);
  }
  const double d = tau / layers, E = 1.0 / mu0;  // beam irradiance: unit flux on the slab
  std::vector<double> I(static_cast<std::size_t>(layers + 1) * 2 * n, 0.0), J(I.size(), 0.0);
  for (int iter = 0; iter < 20000; ++iter) {
    for (int k = 0; k <= layers; ++k) {
      const double beam = albedo * E * std::exp(-k * d / mu0);
      for (int i = 0; i < 2 * n; ++i) {
        double s = 0.0;
        for (int j = 0; j < 2 * n; ++j) s += 2.0 * M_PI * wt[j] * P[i * 2 * n + j] * I[k * 2 * n + j];
        J[k * 2 * n + i] = albedo * s + beam * Pbeam[i];
      }
    }
    double change = 0.0;
    for (int i = 0; i < 2 * n; ++i) {
      const double a = std::exp(-d / std::abs(mu[i]));
      if (mu[i] > 0) {
        for (int k = 0; k < layers; ++k) {
          const double v = I[k * 2 * n + i] * a + 0.5 * (J[k * 2 * n + i] + J[(k + 1) * 2 * n + i]) * (1.0 - a);
          change = std::max(change, std::abs(v - I[(k + 1) * 2 * n + i]));
          I[(k + 1) * 2 * n + i] = v;
        }
      } else {
        for (int k = layers; k > 0; --k) {
          const double v = I[k * 2 * n + i] * a + 0.5 * (J[k * 2 * n + i] + J[(k - 1) * 2 * n + i]) * (1.0 - a);
          change = std::max(change, std::abs(v - I[(k - 1) * 2 * n + i]));
          I[(k - 1) * 2 * n + i] = v;
        }
      }
    }
    if (change < 1e-11) break;
  }
  SlabSolution rt;
  rt.T = std::exp(-tau / mu0);
  for (int i = 0; i < n; ++i) {
    rt.T += 2.0 * M_PI * wt[i] * mu[i] * I[static_cast<std::size_t>(layers) * 2 * n + i];
    rt.R += 2.0 * M_PI * wt[n + i] * x[i] * I[n + i];
  }
  for (int k = 0; k <= layers; ++k) {
    double f = 0.0, q = 0.0, m2 = 0.0;
    for (int i = 0; i < 2 * n; ++i) {
      f += 2.0 * M_PI * wt[i] * I[static_cast<std::size_t>(k) * 2 * n + i];
      q += 2.0 * M_PI * wt[i] * mu[i] * I[static_cast<std::size_t>(k) * 2 * n + i];
      m2 += 2.0 * M_PI * wt[i] * (mu[i] * mu[i] - 1.0 / 3.0) * I[static_cast<std::size_t>(k) * 2 * n + i];
    }
    rt.second.push_back(m2);
    rt.tau.push_back(k * d);
    rt.fluence.push_back(f);
    rt.flux_down.push_back(q);
  }
  return rt;
}

}  // namespace nimbus::render::test
