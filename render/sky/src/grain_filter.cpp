// The still's grain filter (grain_filter.hpp).
#include "nimbus/render/sky/grain_filter.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace nimbus::render {

void validate(const GrainFilter& filter) {
  if (!(filter.sigma_px > 0.0 && filter.sigma_px <= 4.0))
    throw std::invalid_argument("grain filter sigma_px: must be in (0, 4] pixels, got " + std::to_string(filter.sigma_px));
  if (!(filter.depth_tolerance > 0.0 && std::isfinite(filter.depth_tolerance)))
    throw std::invalid_argument("grain filter depth_tolerance: must be finite and > 0, got " +
                                std::to_string(filter.depth_tolerance));
  if (filter.off_from_samples < 1) throw std::invalid_argument("grain filter off_from_samples: must be at least 1");
}

bool grain_filter_applies(const GrainFilter& filter, unsigned samples, bool jitter) {
  return filter.on && jitter && samples < filter.off_from_samples;
}

double grain_filter_sigma_px(const GrainFilter& filter, unsigned samples) {
  const double n = std::max(1u, samples);
  return filter.sigma_px * std::max(0.6, 1.0 - 0.1 * std::log2(n));
}

namespace {

// What a pixel shows, for the filter: a surface (untouched, taken by no one), clouds (with a
// distance), or the sky behind them.
enum class Shows : unsigned char { Sky, Clouds, Surface };

std::vector<Shows> classify(const PixelDepths& depths) {
  std::vector<Shows> shows(static_cast<std::size_t>(depths.width) * depths.height);
  for (int y = 0; y < depths.height; ++y)
    for (int x = 0; x < depths.width; ++x) {
      const float d = depths.distance_m(x, y);
      shows[static_cast<std::size_t>(y) * depths.width + x] =
          depths.on_clouds(x, y) && d > 0.0f ? Shows::Clouds : (d > 0.0f ? Shows::Surface : Shows::Sky);
    }
  return shows;
}

// Whether any cloud pixel lies within `r` pixels (a square): elsewhere the sky is smooth and the
// filter would change nothing worth its time.
std::vector<char> near_clouds(const std::vector<Shows>& shows, int w, int h, int r) {
  std::vector<char> row(shows.size(), 0), out(shows.size(), 0);
  for (int y = 0; y < h; ++y) {
    int last = -1 - r;  // the last cloud pixel seen to the left
    for (int x = 0; x < w + r; ++x) {
      if (x < w && shows[static_cast<std::size_t>(y) * w + x] == Shows::Clouds) last = x;
      if (x - r >= 0 && x - last <= 2 * r) row[static_cast<std::size_t>(y) * w + (x - r)] = 1;
    }
  }
  for (int x = 0; x < w; ++x) {
    int last = -1 - r;
    for (int y = 0; y < h + r; ++y) {
      if (y < h && row[static_cast<std::size_t>(y) * w + x]) last = y;
      if (y - r >= 0 && y - last <= 2 * r) out[static_cast<std::size_t>(y - r) * w + x] = 1;
    }
  }
  return out;
}

// Each cloud pixel's distance for the depth weights: the median of the cloud pixels' distances
// in its 3x3 neighbourhood. The distance is an alpha-weighted mean of grainy samples: a pixel at
// a cloud's edge whose few samples fell on the clouds far behind reads their distance, and
// weighed against its own reading it took nothing from its neighbours and kept its grain (dark
// dots along the congestus' edge in README command 1's picture at 300 %).
std::vector<float> reference_depths(const PixelDepths& depths, const std::vector<Shows>& shows) {
  const int w = depths.width, h = depths.height;
  std::vector<float> out(shows.size(), 0.0f);
  tbb::parallel_for(0, h, [&](int y) {
    float near[9];
    for (int x = 0; x < w; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * w + x;
      if (shows[p] != Shows::Clouds) continue;
      int n = 0;
      for (int j = std::max(0, y - 1); j <= std::min(h - 1, y + 1); ++j)
        for (int i = std::max(0, x - 1); i <= std::min(w - 1, x + 1); ++i)
          if (shows[static_cast<std::size_t>(j) * w + i] == Shows::Clouds) near[n++] = depths.distance_m(i, j);
      std::nth_element(near, near + n / 2, near + n);
      out[p] = near[n / 2];
    }
  });
  return out;
}

// Sums of `v` over the (2r + 1)^2 square about each pixel (edges clamped to the image).
std::vector<double> box_sums(const std::vector<double>& v, int w, int h, int r) {
  std::vector<double> rows(v.size()), out(v.size());
  for (int y = 0; y < h; ++y) {
    const double* in = &v[static_cast<std::size_t>(y) * w];
    std::vector<double> prefix(w + 1, 0.0);
    for (int x = 0; x < w; ++x) prefix[x + 1] = prefix[x] + in[x];
    for (int x = 0; x < w; ++x) rows[static_cast<std::size_t>(y) * w + x] = prefix[std::min(w, x + r + 1)] - prefix[std::max(0, x - r)];
  }
  std::vector<double> prefix(h + 1);
  for (int x = 0; x < w; ++x) {
    prefix[0] = 0.0;
    for (int y = 0; y < h; ++y) prefix[y + 1] = prefix[y] + rows[static_cast<std::size_t>(y) * w + x];
    for (int y = 0; y < h; ++y) out[static_cast<std::size_t>(y) * w + x] = prefix[std::min(h, y + r + 1)] - prefix[std::max(0, y - r)];
  }
  return out;
}

// Takes the filter's change only where it is grain. What the filter removes, r = I - F, is
// grain or detail: blue-noise grain flips sign from pixel to pixel (its removed part's
// correlation with its 4 neighbours, over a window, is negative: -0.22 on README command 1's
// picture), where the detail of clouds is smooth at that scale (+0.5 to +0.6 on a near sky, from
// one frame or from the mean of 32). Each pixel keeps the share a = (0.3 - c) / 0.4 of the
// change, clamped to [0, 1], c its window's correlation, times a share for how evenly the change
// fills the window (below). Measured with `nimbus compare` against the mean of 32 jittered
// frames: a near sky with little grain (two cumulus at 60 m voxels seen from 4 km, 192x108)
// 0.76 % unfiltered, 0.79 % filtered, 2.0 % with the change taken everywhere; README command 1's
// picture 7.0 % -> 1.37 % (against 64 frames). `out` holds F and becomes the blend; returns the
// mean share over the filtered pixels. `reach`: the share of each pixel's kernel its neighbours
// took.
double blend_by_grain(const Image& frame, Image& out, const std::vector<Shows>& shows, const std::vector<char>& active,
                      const std::vector<float>& reach) {
  constexpr int kWindow = 6;  // the window's half side, pixels
  constexpr double kGrain = -0.1, kDetail = 0.3;
  constexpr double kSparse = 0.15, kDense = 0.35;
  const int w = frame.width, h = frame.height;
  const auto taken = [&](std::size_t p) { return active[p] && shows[p] != Shows::Surface; };
  std::vector<double> removed(shows.size(), 0.0);
  for (std::size_t p = 0; p < removed.size(); ++p)
    if (taken(p)) {
      const float* a = &frame.rgba[4 * p];
      const float* f = &out.rgba[4 * p];
      removed[p] = ((a[0] - f[0]) + (a[1] - f[1]) + (a[2] - f[2])) / 3.0;
    }
  std::vector<double> energy(removed.size()), lag(removed.size()), size(removed.size()), count(removed.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * w + x;
      const double r = removed[p];
      energy[p] = r * r;
      size[p] = std::abs(r);
      count[p] = taken(p) ? 1.0 : 0.0;
      double n = 0.0;
      if (x > 0) n += removed[p - 1];
      if (x + 1 < w) n += removed[p + 1];
      if (y > 0) n += removed[p - w];
      if (y + 1 < h) n += removed[p + w];
      lag[p] = 0.25 * r * n;
    }
  const std::vector<double> e = box_sums(energy, w, h, kWindow), c = box_sums(lag, w, h, kWindow);
  const std::vector<double> l1 = box_sums(size, w, h, kWindow), n = box_sums(count, w, h, kWindow);
  double shares = 0.0;
  int counted = 0;
  for (std::size_t p = 0; p < removed.size(); ++p) {
    if (!taken(p)) continue;
    const double correlation = e[p] > 0.0 ? c[p] / e[p] : 1.0;
    // Grain fills its window; a feature a pixel or two wide (a far wisp in a small frame) is as
    // jagged but holds its change in a few pixels: (sum |r|)^2 / (n sum r^2) is 2/pi for
    // Gaussian noise, 1/n for one pixel.
    const double spread = e[p] > 0.0 ? l1[p] * l1[p] / (std::max(n[p], 1.0) * e[p]) : 0.0;
    // A mean over one side of the window (beside the ground, or a cloud at another distance)
    // moves the pixel along its gradient: measured, the cumulus edges over the ground of a near
    // sky. Kept in full only where the neighbours took 80 % of the kernel, none below 50 %.
    const double share = std::clamp((kDetail - correlation) / (kDetail - kGrain), 0.0, 1.0) *
                         std::clamp((spread - kSparse) / (kDense - kSparse), 0.0, 1.0) *
                         std::clamp((reach[p] - 0.5) / 0.3, 0.0, 1.0);
    for (int k = 0; k < 4; ++k) out.rgba[4 * p + k] = static_cast<float>(frame.rgba[4 * p + k] + share * (out.rgba[4 * p + k] - frame.rgba[4 * p + k]));
    shares += share;
    ++counted;
  }
  return counted > 0 ? shares / counted : 0.0;
}

}  // namespace

Image filter_grain(const Image& frame, const PixelDepths& depths, const GrainFilter& filter) {
  validate(filter);
  const int w = frame.width, h = frame.height;
  const bool guided = !depths.empty();
  if (guided && (depths.width != w || depths.height != h || depths.values.size() != static_cast<std::size_t>(w) * h * 2))
    throw std::invalid_argument("grain filter depths: " + std::to_string(depths.width) + "x" +
                                std::to_string(depths.height) + ", not the frame's " + std::to_string(w) + "x" +
                                std::to_string(h));
  // The Gaussian to 2.5 sigma (the weights are normalised, so the cut changes only the tail).
  const int r = std::max(1, static_cast<int>(std::ceil(2.5 * filter.sigma_px)));
  std::vector<double> g(2 * r + 1);
  for (int i = -r; i <= r; ++i) g[i + r] = std::exp(-0.5 * (i * i) / (filter.sigma_px * filter.sigma_px));
  // Without depths (clouds alone, no scene under them: the image's alpha is theirs), every pixel
  // is filtered, by distance in the image alone.
  const std::vector<Shows> shows = guided ? classify(depths) : std::vector<Shows>(static_cast<std::size_t>(w) * h, Shows::Sky);
  const std::vector<char> active = guided ? near_clouds(shows, w, h, r) : std::vector<char>(shows.size(), 1);
  const double inv_tol = 1.0 / filter.depth_tolerance;
  const std::vector<float> reference = guided ? reference_depths(depths, shows) : std::vector<float>();
  Image out = frame;
  // The share of the pixel's kernel (within the image) that its neighbours took: less where
  // surfaces or clouds at other distances stood in the window (blend_by_grain).
  std::vector<float> reach(shows.size(), 1.0f);
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * w + x;
      if (!active[p] || shows[p] == Shows::Surface) continue;
      const bool p_cloud = shows[p] == Shows::Clouds;
      const double dp = p_cloud ? reference[p] : 0.0;
      double sum[4] = {0.0, 0.0, 0.0, 0.0}, total = 0.0, full = 0.0;
      for (int j = std::max(0, y - r); j <= std::min(h - 1, y + r); ++j)
        for (int i = std::max(0, x - r); i <= std::min(w - 1, x + r); ++i) {
          const Shows s = shows[static_cast<std::size_t>(j) * w + i];
          double weight = g[i - x + r] * g[j - y + r];
          full += weight;
          if (s == Shows::Surface) continue;
          if (p_cloud && s == Shows::Clouds) {
            // 1 / (1 + (relative difference / tolerance)^2): a half at the tolerance.
            const double dq = depths.distance_m(i, j);
            const double rel = (dq - dp) / std::min(dp, dq) * inv_tol;
            weight /= 1.0 + rel * rel;
          }
          const float* c = frame.pixel(i, j);
          for (int k = 0; k < 4; ++k) sum[k] += weight * c[k];
          total += weight;
        }
      float* o = out.pixel(x, y);
      // total > 0: the pixel's own weight is positive (its distance against its neighbours' median).
      for (int k = 0; k < 4; ++k) o[k] = static_cast<float>(sum[k] / total);
      reach[p] = static_cast<float>(total / full);
    }
  });
  const double share = blend_by_grain(frame, out, shows, active, reach);
  std::ostringstream m;
  m << "sigma " << filter.sigma_px << " px, depth tolerance " << filter.depth_tolerance << ", "
    << "its change kept on " << std::lround(100.0 * share) << " % (mean over the pixels near clouds)";
  out.metadata["grain_filter"] = m.str();
  return out;
}

Image still_picture(const Image& mean, unsigned samples, const PixelDepths& depths, const GrainFilter& filter, bool jitter) {
  if (!grain_filter_applies(filter, samples, jitter)) return mean;
  GrainFilter narrowed = filter;
  narrowed.sigma_px = grain_filter_sigma_px(filter, samples);
  return filter_grain(mean, depths, narrowed);
}

}  // namespace nimbus::render
