// Model only what the samples can show: the octave count of a fractal sum chosen so that no
// octave's band lies above the Nyquist limit of the sample spacing.
#pragma once
#include "nimbus/noise/params.hpp"

namespace nimbus::noise {

// Top of one octave's band in cycles per lattice unit: above it each kind keeps only a small
// share of its energy (128^3 spectra measured independently of nimbus: the best octave of
// Perlin's 2002 reference is [0.5, 1), of FastNoiseLite's value noise [0.34, 0.69); wavelet
// noise's nominal band, after Cook & DeRose 2005, is [0.25, 0.5)).
double band_top(Kind kind);

struct OctaveChoice {
  int octaves;           // octaves to evaluate (>= 1, <= the requested count)
  int requested;         // octaves asked for
  double nyquist;        // 1 / (2 spacing), cycles per input unit
  double top_frequency;  // band top of the last kept octave, cycles per input unit
  bool first_aliased;    // even the first octave lies above Nyquist (kept anyway)
};

// Samples `spacing` input units apart (a voxel, or a pixel's footprint) resolve octave i when
// frequency * lacunarity^i * band_top(kind) <= 1 / (2 spacing).
OctaveChoice octaves_for_footprint(const NoiseParams& p, double spacing);

// p with its octave count limited by the footprint; the choice is reported through `choice`.
NoiseParams limit_octaves(NoiseParams p, double spacing, OctaveChoice* choice = nullptr);

}  // namespace nimbus::noise
