// The exact range of Perlin's improved gradient noise, used to scale it into [-1, 1].
//
// With quintic fade weights w_c >= 0, the largest value in a cell is reached when every
// corner c takes the edge gradient that maximises g . d_c, i.e. the sum of the (dims - 1)
// largest |d_c| components. gradient_noise_bound() maximises that over the cell in double
// precision. In 3D the maximum is 1.0363538 at p = (0.3553, 0.4815, 0.5) and its mirror
// images (FastNoiseLite's scale 0.964921414852 is its reciprocal).
#pragma once

namespace nimbus::noise {

// Scale factors applied to the raw noise: slightly below 1/bound, so that the scaled float
// noise can never exceed 1 (tests check both the bound and the scaled extremum).
inline constexpr float kGradientBound3 = 1.0363538f;
inline constexpr float kGradientScale3 = 1.0f / 1.03635395f;
inline constexpr float kGradientBound4 = 1.5365823f;
inline constexpr float kGradientScale4 = 1.0f / 1.5365825f;

struct BoundResult {
  double bound;    // max over the cell of the best-gradient sum
  double p[4];     // where it is reached (first `dims` entries used)
};

// dims is 3 or 4. Deterministic; takes a few tens of milliseconds.
BoundResult gradient_noise_bound(int dims);

// Maximum over gradients of sum_c w_c(p) (g_c . d_c) at one point p of the cell.
double best_gradient_sum(int dims, const double* p);

}  // namespace nimbus::noise
