// Power spectra of sampled 2D/3D signals for the spectral tests (docs/noise.md, "Spectra"):
// mean removed, separable Hann window, real FFT (kissfft, float), power binned by radial
// frequency |f|. Frequencies are in cycles per unit of `spacing` (cycles per lattice unit when
// a noise with frequency 1 is sampled `spacing` lattice units apart).
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace nimbus::test {

enum class Window { None, Hann };

// [lo, hi) in cycles per unit.
struct Band {
  double lo;
  double hi;
};

struct ConeStats {
  double power = 0.0;  // summed power of the frequency samples inside the cones
  double count = 0.0;  // how many frequency samples that is (full spectrum, both signs)
  double density() const { return count > 0.0 ? power / count : 0.0; }
};

class PowerSpectrum {
 public:
  // samples: dims[0] * dims[1] * dims[2] values, x fastest. dims[2] == 1 gives a 2D spectrum
  // (frequencies (fx, fy, 0)). dims[0] must be even, dims[0] and dims[1] at least 2. The power
  // is normalised so that total() is the mean square of the windowed, mean-removed samples
  // (Parseval); a periodic Hann window keeps (3/8)^d of a stationary signal's power.
  PowerSpectrum(std::span<const float> samples, std::array<int, 3> dims, double spacing,
                Window window = Window::Hann, bool remove_mean = true);

  // Adds another spectrum of the same shape and spacing (e.g. several 2D slices).
  void accumulate(const PowerSpectrum& other);

  std::array<int, 3> dims() const { return dims_; }
  double spacing() const { return spacing_; }
  // Frequency resolution along each axis, and the Nyquist limit (the same on every axis).
  double df(int axis) const { return 1.0 / (dims_[axis] * spacing_); }
  double nyquist() const { return 0.5 / spacing_; }

  double total() const { return prefix_.empty() ? 0.0 : prefix_.back(); }
  // Energy of the samples with lo <= |f| < hi, and that as a share of total().
  double energy(Band b) const;
  double share(Band b) const { return energy(b) / total(); }
  double share_below(double f) const { return energy({-1.0, f}) / total(); }
  double share_at_or_above(double f) const { return 1.0 - share_below(f); }

  // Energy per radial bin [i w, (i + 1) w) for |f| up to max_f (default: the largest |f|).
  std::vector<double> radial_histogram(double bin_width, double max_f = -1.0) const;

  // The octave [lo, 2 lo) holding the most energy, over lo in (0, max_lo] (default: Nyquist / 2,
  // so the octave lies inside the inscribed sphere). Every lo at which the band energy can
  // change is tried: each sample radius r (lo = r) and each r / 2 (2 lo = r).
  Band best_octave(double max_lo = -1.0) const;

  // Power and sample count on cones of half-angle half_angle_deg around each direction (one
  // sided: the cone around -d is a separate direction), for frequencies in band b. The
  // spectrum of a real signal is symmetric, so the 6 axis directions give the same density as
  // the 3 positive ones; both signs are accounted for exactly.
  ConeStats cones(std::span<const std::array<double, 3>> directions, double half_angle_deg,
                  Band b) const;

 private:
  struct Entry {
    float f[3];    // frequency vector (one representative of f / -f when mult == 2)
    float r;       // |f|
    double power;  // power of all the bins this entry stands for
    float mult;    // 1: one bin; 2: this bin and its mirror -f (same power each)
  };
  void finish();         // sort by radius, then update_prefix()
  void update_prefix();  // prefix sums of the power

  std::array<int, 3> dims_;
  double spacing_;
  std::vector<Entry> entries_;   // sorted by r
  std::vector<double> prefix_;   // prefix_[i] = sum of power of entries_[0..i]
  std::vector<float> radii_;     // entries_[i].r, for binary search
};

// Direction sets for the isotropy ratio.
const std::vector<std::array<double, 3>>& axis_directions();      // 6: +-x, +-y, +-z
const std::vector<std::array<double, 3>>& diagonal_directions();  // 8: (+-1, +-1, +-1)/sqrt 3

// Axis/diagonal power-density ratio on cones of half_angle_deg within band b: the mean power
// per frequency sample in the 6 axis cones over the same in the 8 body-diagonal cones. A
// density (not a sum) so that the different numbers of lattice frequencies in the two cone
// sets do not bias it; for a continuous spectrum (equal solid angles) the two agree.
double isotropy_ratio(const PowerSpectrum& s, Band b, double half_angle_deg = 10.0);

}  // namespace nimbus::test
