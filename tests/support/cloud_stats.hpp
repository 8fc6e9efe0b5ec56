// Observational statistics of cloud fields, measured on a 2-D map of vertical optical depth
// tau(x, y), so that generated clouds can be compared with satellite and aircraft numbers: the
// perimeter-area fractal dimension D (about 1.35, Lovejoy 1982), the area-distribution exponent
// b of dn/dlog a ∝ a^-b (about 0.87, DeWitt et al. 2024, fitted as DeWitt & Garrett 2024 advise)
// and the 1-D spectral slope of tau (about -5/3 between 200 m and 5 km, Cahalan & Snider 1989).
#pragma once
#include <openvdb/openvdb.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace nimbus::test {

// tau on a regular grid of square pixels.
struct OpticalDepthMap {
  int nx = 0, ny = 0;
  double pixel_m = 0;        // pixel side, metres
  std::vector<double> tau;   // nx * ny values, x fastest
  double at(int i, int j) const { return tau[size_t(j) * size_t(nx) + size_t(i)]; }
};

// The largest map vertical_optical_depth makes (2^26 pixels, 512 MiB of doubles).
inline constexpr int64_t kMaxOpticalDepthPixels = int64_t(1) << 26;

// tau(i, j) = extinction_per_m * voxel_m * sum over k of density(i, j, k), in double, for the
// columns i in [columns.min().x(), columns.max().x()], j in [columns.min().y(), .max().y()] of
// the grid's index space; every k is summed (z is up; the box's z range is ignored). Pixel
// (0, 0) of the map is column (min.x, min.y); pixel_m is the voxel size. Inactive voxels hold
// the background, which must be 0 (a fog volume's). Throws std::invalid_argument for an
// extinction that is not finite and positive, an empty box, a box over kMaxOpticalDepthPixels
// columns (before allocating), a transform that is not a uniform axis-aligned scale (plus any
// translation: index z must be world up and voxels cubes), a non-zero background, or densities
// that make a tau non-finite.
OpticalDepthMap vertical_optical_depth(const openvdb::FloatGrid& density, double extinction_per_m,
                                       const openvdb::CoordBBox& columns);

// One cloud: a 4-connected component of the pixels with tau >= threshold.
struct CloudOutline {
  int64_t pixels = 0;
  double area_m2 = 0;       // pixels * pixel_m^2
  double perimeter_m = 0;   // pixel edges between the cloud and non-cloud pixels (holes and the
                            // map border included), times pixel_m
  bool touches_edge = false;  // has a pixel in the first or last row or column (truncated)
};

// Every cloud of the map, in the raster order (x fastest) of each cloud's first pixel. The
// labelling is an iterative span fill (no recursion: maps can be 4096^2 and one cloud all of it).
// Throws std::invalid_argument for an empty or inconsistent map, a pixel size that is not finite
// and positive, a non-finite threshold or a NaN tau.
std::vector<CloudOutline> cloud_outlines(const OpticalDepthMap& m, double threshold = 1.0);

// A least-squares power law, log10 y = exponent * log10 x + c, and what went into it.
struct PowerLawFit {
  double exponent = 0;        // D, b or the spectral slope: see each function
  double standard_error = 0;  // of the exponent, from the residuals; +infinity from 2 points
  int points = 0;             // clouds or bins in the regression
  double x_lo = 0, x_hi = 0;  // range of the regressor x over those points, in its units
};

// The perimeter-area fractal dimension D of P ∝ sqrt(A)^D (Lovejoy 1982; about 1.35 observed):
// the least-squares slope of log P against log sqrt(A) over the clouds that do not touch the
// edge and have at least min_pixels pixels. x is sqrt(A) in metres. Throws
// std::invalid_argument for min_pixels < 1, a non-finite or non-positive area or perimeter
// among those clouds, fewer than 2 of them, or all of one size.
PowerLawFit perimeter_area_dimension(const std::vector<CloudOutline>& clouds, int64_t min_pixels = 10);

// The exponent b of the cloud-area distribution dn/dlog a ∝ a^-b (DeWitt et al. 2024: about
// 0.87). Clouds touching the edge, or under min_pixels pixels, are left out (edge-truncated
// clouds bias the exponent). Areas fall in log10-spaced bins [10^(n/bpd), 10^((n+1)/bpd)) with
// bpd = bins_per_decade; a bin's dn/dlog a is its count divided by its log10 width 1/bpd; bins
// with fewer than min_count clouds are dropped (DeWitt & Garrett 2024: 24); b is minus the
// least-squares slope of log dn/dlog a against log a at the bins' geometric centres. points is
// the number of bins used; x is area in m^2 (the centres of the first and last bins used).
// Throws std::invalid_argument for bins_per_decade outside [1, 100], min_count < 1,
// min_pixels < 1, a non-finite or non-positive area among the clouds used, or fewer than 2 bins
// left.
PowerLawFit area_exponent(const std::vector<CloudOutline>& clouds, int bins_per_decade = 5, int min_count = 24,
                          int64_t min_pixels = 1);

// Which way a 1-D transect runs through the map.
enum class MapAxis { X, Y };  // X: along rows (i varies); Y: along columns (j varies)

// The log-log slope of the 1-D power spectrum of tau along `along` (Cahalan & Snider 1989: about
// -5/3 between 200 m and 5 km). Each line has its mean removed and a periodic Hann window
// applied; |FFT|^2 (double-precision kissfft) is averaged over the lines. The wavenumbers k =
// m / (n pixel_m), m = 1 .. n/2, with 1/k in [lambda_lo_m, lambda_hi_m] fall in 10 log-spaced
// bins a decade; each non-empty bin contributes one point (mean power, geometric mean k), so
// that each decade weighs the same. The exponent is the slope of log P against log k (negative
// for clouds); x is k in cycles per metre. Throws std::invalid_argument for an empty or
// inconsistent map, a non-finite tau, wavelengths that are not finite with 0 < lambda_lo_m <
// lambda_hi_m, lambda_lo_m under the Nyquist wavelength 2 pixel_m or lambda_hi_m over the line
// length, fewer than 2 bins, or a bin with no power (tau does not vary along the lines there).
// Line lengths with a large prime factor are slow (kissfft's generic radix costs n p a line).
PowerLawFit spectrum_slope(const OpticalDepthMap& m, MapAxis along, double lambda_lo_m, double lambda_hi_m);

}  // namespace nimbus::test
