// Ulichney's void-and-cluster method (R. Ulichney, "The void-and-cluster method for dither
// array generation", SPIE 1913, 1993) with incremental energy updates and per-block extremes.
#include "nimbus/render/core/blue_noise.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nimbus/base/splitmix64.hpp"

namespace nimbus::render {
namespace {

constexpr double kSigma = 1.5;  // pixels, Ulichney's recommended filter width
constexpr int kBlock = 16;      // pixels per side of the blocks whose extremes are cached

using nimbus::SplitMix64;  // a portable generator, unlike std::uniform_int_distribution

// A binary pattern on the torus with its energy E(p) = sum over set pixels q of
// exp(-d(p, q)^2 / (2 sigma^2)) (Ulichney eq. 2), d the toroidal distance, kept up to date as
// pixels toggle. Each block caches its tightest cluster (set pixel of largest E) and largest
// void (unset pixel of smallest E), so a search scans the blocks instead of every pixel.
class Pattern {
 public:
  explicit Pattern(int n)
      : n_(n),
        r_(std::min(static_cast<int>(std::ceil(6.0 * kSigma)), n / 2 - 1)),
        b_(std::min(kBlock, n)),
        nb_(n / b_),
        bits_(static_cast<std::size_t>(n) * n, 0),
        energy_(bits_.size(), 0.0),
        cluster_(static_cast<std::size_t>(nb_) * nb_, -1),
        void_(cluster_.size(), -1) {
    const int w = 2 * r_ + 1;
    kernel_.resize(static_cast<std::size_t>(w) * w);
    for (int dy = -r_; dy <= r_; ++dy) {
      for (int dx = -r_; dx <= r_; ++dx) {
        kernel_[(dy + r_) * w + dx + r_] = std::exp(-(dx * dx + dy * dy) / (2.0 * kSigma * kSigma));
      }
    }
    for (int b = 0; b < nb_ * nb_; ++b) refresh_block(b);
  }

  bool is_set(int p) const { return bits_[p] != 0; }

  void set(int p, bool on) {
    if (is_set(p) == on) return;
    bits_[p] = on ? 1 : 0;
    const double s = on ? 1.0 : -1.0;
    const int x = p % n_, y = p / n_, w = 2 * r_ + 1;
    for (int dy = -r_; dy <= r_; ++dy) {
      const int row = ((y + dy) & (n_ - 1)) * n_;
      const double* k = &kernel_[(dy + r_) * w + r_];
      for (int dx = -r_; dx <= r_; ++dx) energy_[row + ((x + dx) & (n_ - 1))] += s * k[dx];
    }
    // The blocks that the kernel's window touches (at most 3 per axis for r <= 9, block 16).
    int bx[4], by[4], nx = 0, ny = 0;
    for (int d = -r_; d <= r_; ++d) {
      const int cx = ((x + d) & (n_ - 1)) / b_, cy = ((y + d) & (n_ - 1)) / b_;
      if (std::find(bx, bx + nx, cx) == bx + nx && nx < 4) bx[nx++] = cx;
      if (std::find(by, by + ny, cy) == by + ny && ny < 4) by[ny++] = cy;
    }
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) refresh_block(by[j] * nb_ + bx[i]);
    }
  }

  // The set pixel of largest energy; the unset pixel of smallest energy (-1 if none).
  int tightest_cluster() const { return best(cluster_, true); }
  int largest_void() const { return best(void_, false); }

 private:
  void refresh_block(int b) {
    const int x0 = (b % nb_) * b_, y0 = (b / nb_) * b_;
    int c = -1, v = -1;
    for (int y = y0; y < y0 + b_; ++y) {
      for (int x = x0; x < x0 + b_; ++x) {
        const int p = y * n_ + x;
        if (bits_[p]) {
          if (c < 0 || energy_[p] > energy_[c]) c = p;
        } else if (v < 0 || energy_[p] < energy_[v]) {
          v = p;
        }
      }
    }
    cluster_[b] = c;
    void_[b] = v;
  }

  int best(const std::vector<int>& per_block, bool largest) const {
    int out = -1;
    for (const int p : per_block) {
      if (p < 0) continue;
      if (out < 0 || (largest ? energy_[p] > energy_[out] : energy_[p] < energy_[out])) out = p;
    }
    return out;
  }

  int n_, r_, b_, nb_;
  std::vector<std::uint8_t> bits_;
  std::vector<double> energy_;
  std::vector<double> kernel_;
  std::vector<int> cluster_, void_;
};

}  // namespace

std::vector<std::uint32_t> blue_noise_ranks(int size, std::uint32_t seed) {
  if (size < 16 || size > 256 || (size & (size - 1)) != 0) {
    throw std::invalid_argument("blue noise: size must be a power of two in [16, 256], got " + std::to_string(size));
  }
  const int total = size * size;
  Pattern pattern(size);

  // Initial binary pattern: total / 10 random pixels (Fisher-Yates from splitmix64) ...
  std::vector<int> order(total);
  for (int i = 0; i < total; ++i) order[i] = i;
  SplitMix64 rng{seed};
  for (int i = total - 1; i > 0; --i) std::swap(order[i], order[rng.next() % static_cast<std::uint64_t>(i + 1)]);
  const int ones = total / 10;
  for (int i = 0; i < ones; ++i) pattern.set(order[i], true);
  // ... spread out by moving the tightest cluster into the largest void until the pixel removed
  // is itself the largest void (Ulichney section 3). The cap only guards against a cycle.
  for (int iter = 0; iter < 4 * total; ++iter) {
    const int c = pattern.tightest_cluster();
    pattern.set(c, false);
    const int v = pattern.largest_void();
    pattern.set(v, true);
    if (v == c) break;
  }
  const Pattern initial = pattern;

  std::vector<std::uint32_t> rank(total);
  // Phase 1: remove the tightest clusters of the initial pattern, ranks ones - 1 down to 0.
  for (int r = ones - 1; r >= 0; --r) {
    const int c = pattern.tightest_cluster();
    pattern.set(c, false);
    rank[c] = static_cast<std::uint32_t>(r);
  }
  // Phases 2 and 3: fill the largest voids, ranks ones .. total - 1. Ulichney's phase 3 (past
  // half full) ranks the tightest cluster of the unset pixels, whose energy is K - E(p) with K
  // the kernel's sum, the same for every pixel on the torus: it is the largest void of E, so
  // both phases are this one loop.
  pattern = initial;
  for (int r = ones; r < total; ++r) {
    const int v = pattern.largest_void();
    pattern.set(v, true);
    rank[v] = static_cast<std::uint32_t>(r);
  }
  return rank;
}

std::vector<float> blue_noise_tile(int size, std::uint32_t seed) {
  const std::vector<std::uint32_t> rank = blue_noise_ranks(size, seed);
  const double total = static_cast<double>(rank.size());
  std::vector<float> tile(rank.size());
  for (std::size_t i = 0; i < rank.size(); ++i) tile[i] = static_cast<float>((rank[i] + 0.5) / total);
  return tile;
}

}  // namespace nimbus::render
