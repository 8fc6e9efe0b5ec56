// A depth-aware spatial filter of the half-angle slicer's jitter grain, for stills. The slicer
// hides its slice banding by moving each pixel's samples within their slabs by a blue-noise
// offset (cloud_slice.frag.glsl): what was banding becomes grain of high spatial frequency,
// which is what blue noise is made for (Ulichney 1993; Georgiev & Fajardo 2016): a small
// low-pass filter removes most of it and little of the picture. Each cloud or sky pixel becomes
// the Gaussian-weighted mean of its cloud and sky neighbours, a neighbour's weight also falling
// with its distance from the pixel's (the clouds' alpha-weighted mean distance,
// pixel_depths.hpp), so a near cloud's edge does not take the far clouds behind it; surfaces
// (the ground) carry no grain and are neither filtered nor taken. The change is then kept only
// where it is grain: where what it removed flips sign from pixel to pixel and fills its
// neighbourhood, as blue-noise grain does and the smooth detail of clouds, or a feature a pixel
// wide, does not (grain_filter.cpp, blend_by_grain). A mean of many jittered frames
// has little grain left, and the filter's blur would then be the larger error: it is off from
// GrainFilter::off_from_samples on. Measured in docs/clouds.md ("Stills without grain").
#pragma once
#include "nimbus/render/core/image.hpp"
#include "nimbus/render/core/pixel_depths.hpp"

namespace nimbus::render {

struct GrainFilter {
  bool on = true;
  // The spatial Gaussian's standard deviation on one frame, pixels, (0, 4]. A mean of n frames
  // has less grain and takes a narrower one: sigma_px (1 - 0.1 log2 n), at least 0.6 sigma_px
  // (grain_filter_sigma_px). Measured on README command 1's picture against the mean of 64
  // jittered frames: 1.0 px best on one or two frames, 0.8 on 4 to 8, 0.6 on 16.
  double sigma_px = 1.0;
  // The relative difference of distance at which a neighbour's weight halves, > 0. The distance
  // is the clouds' alpha-weighted mean, itself grainy: a tight tolerance keeps grain (0.25: 1.74 %
  // from the mean of 64 frames on README command 1's picture, 1.0: 1.41 %, none: 1.39 %); 1.0
  // still keeps a cloud twice as near as those behind it from taking them (a fifth of the weight).
  double depth_tolerance = 1.0;
  unsigned off_from_samples = 32;  // a mean of this many jittered frames or more is left as it is, >= 1
};

// Throws std::invalid_argument naming the field.
void validate(const GrainFilter& filter);

// Whether the filter changes a still that is the mean of `samples` jittered frames (the jitter
// on): on, and fewer samples than off_from_samples.
bool grain_filter_applies(const GrainFilter& filter, unsigned samples, bool jitter);

// The Gaussian's standard deviation for a mean of `samples` frames (>= 1), pixels.
double grain_filter_sigma_px(const GrainFilter& filter, unsigned samples);

// `frame` filtered with a Gaussian of sigma_px (not narrowed), guided by its `depths` (the same size, from FrameRenderer::render; empty for
// clouds alone, whose alpha is then filtered with their radiance, every pixel by its distance in
// the image alone). The metadata gains "grain_filter". Throws std::invalid_argument when the
// depths are of another size or the filter is invalid.
Image filter_grain(const Image& frame, const PixelDepths& depths, const GrainFilter& filter);

// The picture a still shows: `mean`, the mean of `samples` jittered frames (one frame: 1),
// filtered when grain_filter_applies (by grain_filter_sigma_px of its samples), guided by the
// depths of one of its frames. Every still goes through it: `nimbus render`, its --view-state
// and the viewer.
Image still_picture(const Image& mean, unsigned samples, const PixelDepths& depths, const GrainFilter& filter, bool jitter);

}  // namespace nimbus::render
