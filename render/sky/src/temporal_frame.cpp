// Temporal upsampling with reprojection (temporal_frame.hpp).
#include "nimbus/render/sky/temporal_frame.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "nimbus/render/sky/progressive_frame.hpp"

namespace nimbus::render {
namespace {

// A smooth bump of a squared distance: (1 - d2 / r2)^2 within r, 0 beyond (a cheap Gaussian).
inline double bump(double d2, double r2) {
  const double t = std::max(0.0, 1.0 - d2 / r2);
  return t * t;
}

// How much a clipped history is still trusted: its weight times exp(-kTrust m), m how far the
// clip moved it, as a share of the clip's range (a history the new samples disown counts for
// little). And the weight of the new frame upsampled, always in the blend: where the history is
// gone, the pixel is what the frame alone would show, not its nearest point sample. Chosen on
// the default sky orbiting at 1 and 1.8 degrees a frame at a quarter of the pixels (docs/viewer.md).
constexpr double kTrust = 20.0, kUpsampled = 1.0;

// The history is clipped to the new samples' weighted mean +- this many standard deviations.
constexpr double kClipSpread = 1.25;

// A camera's frame and image plane, with pixel centres at whole coordinates: pixel (i, j) is at
// (i, j), row 0 at the top (the pixel_ray convention less its half pixel).
struct View {
  glm::dvec3 eye, right, up, forward;
  double half_x = 1.0, half_y = 1.0;  // tan of the half field of view, across and up
  int width = 1, height = 1;
  glm::dvec2 offset{0.0};
};

View view_of(const Camera& c) {
  const CameraFrame f = camera_frame(c);
  View v;
  v.eye = c.eye;
  v.right = f.right;
  v.up = f.up;
  v.forward = f.forward;
  v.half_x = std::tan(0.5 * c.fov_deg * M_PI / 180.0);
  v.half_y = v.half_x * c.height / c.width;
  v.width = c.width;
  v.height = c.height;
  v.offset = c.pixel_offset;
  return v;
}

glm::dvec3 centre_ray(const View& v, int x, int y) {
  const double nx = 2.0 * (x + 0.5) / v.width - 1.0, ny = 1.0 - 2.0 * (y + 0.5) / v.height;
  return glm::normalize(v.forward + (nx * v.half_x) * v.right + (ny * v.half_y) * v.up);
}

// Where `rel` (a point less the eye, or a direction) lands on v's image, in pixel-centre
// coordinates; false behind the eye.
bool project(const View& v, const glm::dvec3& rel, glm::dvec2& at) {
  const double z = glm::dot(rel, v.forward);
  if (!(z > 1e-9 * glm::length(rel))) return false;
  const double nx = glm::dot(rel, v.right) / (z * v.half_x), ny = glm::dot(rel, v.up) / (z * v.half_y);
  at = {(nx + 1.0) * 0.5 * v.width - 0.5, (1.0 - ny) * 0.5 * v.height - 0.5};
  return std::isfinite(at.x) && std::isfinite(at.y);
}

struct Rgba {
  float c[4] = {0, 0, 0, 0};
};

// Bilinear interpolation of an N-channel plane at (x, y) in pixel-centre coordinates, clamped
// at the edges: the new frame (N = 4) and the history's weights (N = 1).
template <int N>
std::array<float, N> bilinear(const std::vector<float>& plane, int w, int h, double x, double y) {
  const double fx = std::floor(x), fy = std::floor(y);
  const float tx = static_cast<float>(x - fx), ty = static_cast<float>(y - fy);
  const int x0 = std::clamp(static_cast<int>(fx), 0, w - 1), x1 = std::clamp(static_cast<int>(fx) + 1, 0, w - 1);
  const int y0 = std::clamp(static_cast<int>(fy), 0, h - 1), y1 = std::clamp(static_cast<int>(fy) + 1, 0, h - 1);
  const auto at = [&](int i, int j) { return plane.data() + (static_cast<std::size_t>(j) * w + i) * N; };
  const float *a = at(x0, y0), *b = at(x1, y0), *c = at(x0, y1), *d = at(x1, y1);
  std::array<float, N> out;
  for (int k = 0; k < N; ++k)
    out[k] = (1 - ty) * ((1 - tx) * a[k] + tx * b[k]) + ty * ((1 - tx) * c[k] + tx * d[k]);
  return out;
}

// Catmull-Rom weights of the four texels around t in [0, 1).
void catmull_rom(float t, float w[4]) {
  const float t2 = t * t, t3 = t2 * t;
  w[0] = 0.5f * (-t3 + 2 * t2 - t);
  w[1] = 0.5f * (3 * t3 - 5 * t2 + 2);
  w[2] = 0.5f * (-3 * t3 + 4 * t2 + t);
  w[3] = 0.5f * (t3 - t2);
}

// The history read with a Catmull-Rom filter: a resampling that stays sharp frame after frame
// (its overshoot is clamped afterwards, with the neighbourhood).
Rgba bicubic(const std::vector<float>& img, int w, int h, double x, double y) {
  const double fx = std::floor(x), fy = std::floor(y);
  float wx[4], wy[4];
  catmull_rom(static_cast<float>(x - fx), wx);
  catmull_rom(static_cast<float>(y - fy), wy);
  const int x0 = static_cast<int>(fx) - 1, y0 = static_cast<int>(fy) - 1;
  int xs[4], ys[4];
  for (int i = 0; i < 4; ++i) {
    xs[i] = std::clamp(x0 + i, 0, w - 1) * 4;
    ys[i] = std::clamp(y0 + i, 0, h - 1);
  }
  Rgba out;
  for (int j = 0; j < 4; ++j) {
    const float* row = img.data() + static_cast<std::size_t>(ys[j]) * w * 4;
    float r[4] = {0, 0, 0, 0};
    for (int i = 0; i < 4; ++i) {
      const float* t = row + xs[i];
      for (int k = 0; k < 4; ++k) r[k] += wx[i] * t[k];
    }
    for (int k = 0; k < 4; ++k) out.c[k] += wy[j] * r[k];
  }
  return out;
}

// A small-frame pixel's 3x3 neighbourhood: its samples' mean, mean square and extremes per
// channel; and the distance (0: the sky) the pixel is carried by, and whether it is the clouds': its own, or
// the nearest cloud's among its neighbours when one is nearer (a cloud's edge over the sky or
// the ground moves with the cloud, Karis 2014's nearest depth; a surface keeps its own, which on
// a ground seen at a grazing angle differs from row to row).
struct Neighbourhood {
  float mean[4] = {0, 0, 0, 0}, meansq[4] = {0, 0, 0, 0}, lo[4] = {0, 0, 0, 0}, hi[4] = {0, 0, 0, 0};
  float distance = 0.0f;
  bool clouds = false;  // the distance is the clouds'
};

std::vector<Neighbourhood> neighbourhoods(const Image& frame, const PixelDepths& depths) {
  const int w = frame.width, h = frame.height;
  std::vector<Neighbourhood> out(static_cast<std::size_t>(w) * h);
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < w; ++x) {
        Neighbourhood& n = out[static_cast<std::size_t>(y) * w + x];
        for (int c = 0; c < 4; ++c) n.lo[c] = n.hi[c] = frame.pixel(x, y)[c];
        int count = 0;
        for (int j = std::max(0, y - 1); j <= std::min(h - 1, y + 1); ++j)
          for (int i = std::max(0, x - 1); i <= std::min(w - 1, x + 1); ++i) {
            const float* p = frame.pixel(i, j);
            ++count;
            for (int c = 0; c < 4; ++c) {
              n.mean[c] += p[c];
              n.meansq[c] += p[c] * p[c];
              n.lo[c] = std::min(n.lo[c], p[c]);
              n.hi[c] = std::max(n.hi[c], p[c]);
            }
          }
        if (!depths.empty()) {
          n.distance = depths.distance_m(x, y);
          n.clouds = depths.on_clouds(x, y);
          for (int j = std::max(0, y - 1); j <= std::min(h - 1, y + 1); ++j)
            for (int i = std::max(0, x - 1); i <= std::min(w - 1, x + 1); ++i) {
              const float d = depths.distance_m(i, j);
              if (depths.on_clouds(i, j) && d > 0.0f && (n.distance == 0.0f || d < n.distance)) {
                n.distance = d;
                n.clouds = true;
              }
            }
        }
        for (int c = 0; c < 4; ++c) {
          n.mean[c] /= count;
          n.meansq[c] /= count;
        }
      }
  });
  return out;
}

// The statistics' mean and mean square read bilinearly at (x, y) of the small frame.
Neighbourhood blend_stats(const std::vector<Neighbourhood>& stats, int w, int h, double x, double y) {
  const double fx = std::floor(x), fy = std::floor(y);
  const float tx = static_cast<float>(x - fx), ty = static_cast<float>(y - fy);
  const int x0 = std::clamp(static_cast<int>(fx), 0, w - 1), x1 = std::clamp(static_cast<int>(fx) + 1, 0, w - 1);
  const int y0 = std::clamp(static_cast<int>(fy), 0, h - 1), y1 = std::clamp(static_cast<int>(fy) + 1, 0, h - 1);
  const Neighbourhood* q[4] = {&stats[static_cast<std::size_t>(y0) * w + x0], &stats[static_cast<std::size_t>(y0) * w + x1],
                               &stats[static_cast<std::size_t>(y1) * w + x0], &stats[static_cast<std::size_t>(y1) * w + x1]};
  const float wt[4] = {(1 - tx) * (1 - ty), tx * (1 - ty), (1 - tx) * ty, tx * ty};
  Neighbourhood m;
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 4; ++c) {
      m.mean[c] += wt[i] * q[i]->mean[c];
      m.meansq[c] += wt[i] * q[i]->meansq[c];
    }
  return m;
}

// What one output pixel needs: the new frame and its statistics, the three views (the output's,
// the small frame's with its offset, the history's), the clouds' shift and the history.
struct Resolve {
  const Image& frame;
  const std::vector<Neighbourhood>& stats;
  View now, small, before;
  double aspect;         // the output's vertical half-extent over the small frame's (rounded sizes)
  glm::dvec2 spacing;    // output pixels per small-frame pixel
  glm::dvec3 cloud_shift_m;
  const Image* history;  // null: none to carry
  const std::vector<float>& weight;
  double max_history;
};

// The range the history is clipped to: the samples' mean and spread around the pixel, read
// bilinearly from the small frame's 3x3 statistics (so the range changes smoothly from pixel to
// pixel, Salvi 2016's variance clipping), within the nearest sample's neighbourhood's extremes.
void clip_range(const Resolve& r, const Neighbourhood& n, const glm::dvec2& at_sample, Rgba& lo, Rgba& hi) {
  const Neighbourhood m = blend_stats(r.stats, r.frame.width, r.frame.height, at_sample.x, at_sample.y);
  for (int c = 0; c < 4; ++c) {
    const double spread = std::sqrt(std::max(0.0f, m.meansq[c] - m.mean[c] * m.mean[c]));
    lo.c[c] = static_cast<float>(std::max<double>(n.lo[c], m.mean[c] - kClipSpread * spread));
    hi.c[c] = static_cast<float>(std::min<double>(n.hi[c], m.mean[c] + kClipSpread * spread));
    if (lo.c[c] > hi.c[c]) lo.c[c] = hi.c[c] = 0.5f * (lo.c[c] + hi.c[c]);
  }
}

// The history where this pixel's surface was in the last frame (the clouds carried by the
// wind), clipped, and its weight. Where there is none (no last frame, or the surface was not in
// it), the new frame upsampled stands in, worth one sample.
double carry_history(const Resolve& r, const glm::dvec3& dir, const Neighbourhood& n, const Rgba& lo, const Rgba& hi,
                     const Rgba& upsampled, Rgba& carried) {
  carried = upsampled;
  if (!r.history) return 1.0;
  const int w = r.history->width, h = r.history->height;
  glm::dvec3 rel = dir;  // the sky: by direction
  if (n.distance > 0.0) rel = r.now.eye + static_cast<double>(n.distance) * dir - (n.clouds ? r.cloud_shift_m : glm::dvec3(0.0)) - r.before.eye;
  glm::dvec2 from;
  if (!project(r.before, rel, from) || from.x < -0.5 || from.y < -0.5 || from.x > w - 0.5 || from.y > h - 0.5) return 1.0;
  carried = bicubic(r.history->rgba, w, h, from.x, from.y);
  double moved = 0.0;  // how far the clip moved it, as a share of the clip's range
  for (int c = 0; c < 4; ++c) {
    const float clipped = std::clamp(carried.c[c], lo.c[c], hi.c[c]);
    if (c < 3) moved = std::max(moved, std::abs(clipped - carried.c[c]) / (1e-6 + hi.c[c] - lo.c[c]));
    carried.c[c] = clipped;
  }
  return bilinear<1>(r.weight, w, h, from.x, from.y)[0] * std::exp(-kTrust * moved);
}

// One output pixel: the carried history, the nearest new sample and the new frame upsampled,
// blended by their weights. Writes its RGBA and returns the history weight it leaves.
float resolve_pixel(const Resolve& r, int x, int y, float* out) {
  const int fw = r.frame.width, fh = r.frame.height;
  const glm::dvec3 dir = centre_ray(r.now, x, y);
  // This pixel's centre on the small frame's grid (its samples at whole + offset): the same
  // view, whose height may be rounded to another aspect.
  const double nx = 2.0 * (x + 0.5) / r.now.width - 1.0, ny = 1.0 - 2.0 * (y + 0.5) / r.now.height;
  const glm::dvec2 at_sample = glm::dvec2((nx + 1.0) * 0.5 * fw - 0.5, (1.0 - ny * r.aspect) * 0.5 * fh - 0.5) - r.small.offset;
  const int si = std::clamp(static_cast<int>(std::lround(at_sample.x)), 0, fw - 1);
  const int sj = std::clamp(static_cast<int>(std::lround(at_sample.y)), 0, fh - 1);
  // The nearest sample, weighted by how near it fell (in output pixels).
  const float* nearest = r.frame.pixel(si, sj);
  const double dx = (si - at_sample.x) * r.spacing.x, dy = (sj - at_sample.y) * r.spacing.y;
  const double k = bump(dx * dx + dy * dy, 1.5);  // near Karis 2014's exp(-2.29 d^2), without the exp
  const Neighbourhood& n = r.stats[static_cast<std::size_t>(sj) * fw + si];
  Rgba lo, hi;
  clip_range(r, n, at_sample, lo, hi);
  Rgba upsampled;
  const std::array<float, 4> up = bilinear<4>(r.frame.rgba, fw, fh, at_sample.x, at_sample.y);
  std::copy(up.begin(), up.end(), upsampled.c);
  Rgba carried;
  const double h = carry_history(r, dir, n, lo, hi, upsampled, carried);
  const double total = h + k + kUpsampled;
  for (int c = 0; c < 4; ++c) {
    const double v = (h * carried.c[c] + k * nearest[c] + kUpsampled * upsampled.c[c]) / total;
    out[c] = std::isfinite(v) ? static_cast<float>(std::max(v, 0.0)) : nearest[c];
  }
  return static_cast<float>(std::min(total, r.max_history));
}

void check_inputs(const Image& frame, const Camera& camera, const PixelDepths& depths, int out_w, int out_h) {
  check_image(frame, "temporal frame");
  validate(camera);
  if (camera.width != frame.width || camera.height != frame.height)
    throw std::invalid_argument("temporal frame: the camera is " + std::to_string(camera.width) + "x" +
                                std::to_string(camera.height) + ", the frame " + std::to_string(frame.width) + "x" +
                                std::to_string(frame.height));
  if (out_w < 1 || out_h < 1 || out_w > 16384 || out_h > 16384)
    throw std::invalid_argument("temporal frame: the output size must be in [1, 16384] pixels per side");
  if (frame.width > out_w || frame.height > out_h)
    throw std::invalid_argument("temporal frame: a " + std::to_string(frame.width) + "x" + std::to_string(frame.height) +
                                " frame is larger than its " + std::to_string(out_w) + "x" + std::to_string(out_h) +
                                " output");
  if (!depths.empty()) {
    if (depths.width != frame.width || depths.height != frame.height ||
        depths.values.size() != 2 * static_cast<std::size_t>(frame.width) * frame.height)
      throw std::invalid_argument("temporal frame: its depths are not the frame's size");
    for (const float v : depths.values)
      if (!std::isfinite(v) || v < 0.0f) throw std::invalid_argument("temporal frame: a depth is negative or not finite");
  }
}

}  // namespace

void validate(const TemporalSettings& s) {
  if (!(s.max_history > 0.0 && s.max_history <= 1e6))
    throw std::invalid_argument("temporal settings max_history: must be in (0, 1e6] samples");
}

glm::dvec2 temporal_pixel_offset(unsigned index) { return progressive_sample(index).pixel_offset; }

TemporalFrame::TemporalFrame(TemporalSettings settings) : settings_(settings) { validate(settings_); }

void TemporalFrame::reset() {
  output_ = Image();
  weight_.clear();
  frames_ = 0;
}

const Image& TemporalFrame::add(const Image& frame, const Camera& camera, const PixelDepths& depths, int out_w,
                                int out_h, const glm::dvec3& cloud_shift_m) {
  check_inputs(frame, camera, depths, out_w, out_h);
  if (!(std::isfinite(cloud_shift_m.x) && std::isfinite(cloud_shift_m.y) && std::isfinite(cloud_shift_m.z)))
    throw std::invalid_argument("temporal frame: the clouds' shift is not finite");
  Camera out_camera = camera;
  out_camera.width = out_w;
  out_camera.height = out_h;
  out_camera.pixel_offset = glm::dvec2(0.0);
  Camera small_centred = camera;
  small_centred.pixel_offset = glm::dvec2(0.0);
  const bool history = frames_ > 0 && output_.width == out_w && output_.height == out_h;
  const std::vector<Neighbourhood> stats = neighbourhoods(frame, depths);
  const View now = view_of(out_camera);
  const Resolve r{frame,
                  stats,
                  now,
                  view_of(camera),
                  view_of(camera_),
                  now.half_y / view_of(small_centred).half_y,
                  {static_cast<double>(out_w) / frame.width, static_cast<double>(out_h) / frame.height},
                  cloud_shift_m,
                  history ? &output_ : nullptr,
                  weight_,
                  settings_.max_history};
  Image next(out_w, out_h);
  std::vector<float> next_weight(static_cast<std::size_t>(out_w) * out_h, 0.0f);
  tbb::parallel_for(tbb::blocked_range<int>(0, out_h), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < out_w; ++x)
        next_weight[static_cast<std::size_t>(y) * out_w + x] = resolve_pixel(r, x, y, next.pixel(x, y));
  });
  next.metadata = frame.metadata;
  frames_ = history ? frames_ + 1 : 1;
  next.metadata["temporal_frames"] = std::to_string(frames_);
  next.metadata["temporal_from"] = std::to_string(frame.width) + "x" + std::to_string(frame.height);
  output_ = std::move(next);
  weight_ = std::move(next_weight);
  camera_ = out_camera;
  return output_;
}

}  // namespace nimbus::render
