// The stages of build_light_volume (light_volume_builder.hpp) that do not trace photons, each a
// function of plain arrays with its own test: where the photons start (the launch rectangle),
// the cells' values from the fixed-point tallies (pooled where a cell is barely covered), the
// spike clamp, the smoothing of the anisotropy, eq. MS-4's linear fits, the rings of empty cells
// the lookup reads, and the packing into a LightVolume (docs/clouds.md, "The light volume").
#pragma once
#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "nimbus/render/core/light_volume.hpp"

namespace nimbus::render::light_volume {

// Tallies per cell: fluence RGB (0-2), flux xyz (3-5), the traceless second moment Q xx yy xy xz
// yz (6-10); per lobe order k = 1, 2 its fluence and its flux along the sun's direction (11-14,
// channels' means); the first moment of position about the cell's centre in cells, xyz (15-17).
inline constexpr int kTallies = 18;
inline constexpr int kLobeTally = 11;
inline constexpr int kMomentTally = 15;
// Below this covered fraction a cell pools its 3^3 neighbourhood (a ratio estimator).
inline constexpr double kPoolBelow = 0.5;
// A cell with at least 6 known neighbours holds at most this times their mean fluence.
inline constexpr double kSpike = 2.0;

// The cells of a grid, x fastest.
struct CellGrid {
  int nx = 0, ny = 0, nz = 0;
  std::size_t cells() const { return std::size_t(nx) * std::size_t(ny) * std::size_t(nz); }
  std::size_t index(int i, int j, int k) const {
    return std::size_t(i) + std::size_t(nx) * (std::size_t(j) + std::size_t(ny) * std::size_t(k));
  }
  // Calls f(i, j, k, q) for every cell, x fastest (q = index(i, j, k)).
  template <class F>
  void for_each_cell(const F& f) const {
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) f(i, j, k, index(i, j, k));
  }
  // Cell q's neighbour across face f (0-5: -x, +x, -y, +y, -z, +z; axis f / 2), or false past
  // the grid's edge.
  bool face_neighbour(std::size_t q, int f, std::size_t& r) const {
    int at[3] = {static_cast<int>(q % std::size_t(nx)), static_cast<int>((q / std::size_t(nx)) % std::size_t(ny)),
                 static_cast<int>(q / (std::size_t(nx) * std::size_t(ny)))};
    const int size[3] = {nx, ny, nz};
    at[f / 2] += (f & 1) ? 1 : -1;
    if (at[f / 2] < 0 || at[f / 2] >= size[f / 2]) return false;
    r = index(at[0], at[1], at[2]);
    return true;
  }
  // Calls f(r) for each cell r of the 3^3 neighbourhood of (i, j, k) inside the grid, itself included.
  template <class F>
  void for_neighbourhood(int i, int j, int k, const F& f) const {
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int ni = i + di, nj = j + dj, nk = k + dk;
          if (ni < 0 || ni >= nx || nj < 0 || nj >= ny || nk < 0 || nk >= nz) continue;
          f(index(ni, nj, nk));
        }
  }
};

// The rectangle the photons start from: perpendicular to the propagation l, covering the grid's
// box as seen from the sun, upstream of every corner of it.
struct LaunchRect {
  glm::dvec3 l{0.0}, eu{0.0}, ev{0.0};  // orthonormal: propagation and the rectangle's axes
  double umin = 0, umax = 0, vmin = 0, vmax = 0;  // the box's extent along eu and ev, metres
  double lmin = 0;                                // the most upstream corner along l
  double area_m2() const { return (umax - umin) * (vmax - vmin); }
  // The point at (x, y) in [0, 1)^2 of the rectangle, `back_m` upstream of the box.
  glm::dvec3 origin(double x, double y, double back_m) const {
    return eu * (umin + x * (umax - umin)) + ev * (vmin + y * (vmax - vmin)) + l * (lmin - back_m);
  }
};
LaunchRect launch_rect(const LightVolume& grid, const glm::dvec3& direction_to_sun);

// The part of each cell where a flight's track is tallied (some brick's majorant > 0), the
// centroid of that part about the cell's centre and its variance per axis, in cells.
struct Coverage {
  std::vector<double> covered;
  std::vector<glm::dvec3> centroid, spread;
};

// Each cell's kTallies values and whether it holds cloud.
struct CellValues {
  std::vector<float> value;  // kTallies per cell
  std::vector<char> known;   // 1 where covered > 0 (or filled by fill_empty_rings)
};

// Track length per volume (eq. MS-2): value = scale * tally / covered, where scale turns a
// tally's fixed-point sum into fluence per unit irradiance; a cell covered less than kPoolBelow
// takes its 3^3 neighbourhood's sum of tallies over their sum of covered fractions.
CellValues cell_values(const CellGrid& g, const std::vector<std::int64_t>& tally,
                       const std::vector<double>& covered, double scale);

// A known cell whose mean fluence exceeds kSpike times its known neighbours' mean (with at least
// 6 of them) has all its values scaled down together to that bound (its anisotropy kept).
void clamp_spikes(const CellGrid& g, CellValues& v);

// Each known cell's flux and second moment become the fluence-weighted mean anisotropy of its
// known 3^3 neighbourhood: F = phi sum(F) / sum(phi), the same for Q; the fluence stays.
void smooth_anisotropy(const CellGrid& g, CellValues& v);

// Eq. MS-4's fit in cells covered at least kPoolBelow: the gradient g (per cell) from the first
// moment and the covered part's centroid and spread, limited so that the fit stays >= 0 over
// the cell; 4 floats per cell: g and dot(g, ubar) (ubar the covered part's centroid, in cells).
std::vector<float> linear_fits(const CellGrid& g, const CellValues& v, const Coverage& c);

// Cells with no cloud take the mean of their known face neighbours (values and fits), ring by
// ring: the trilinear lookup of a neighbour reads them.
void fill_empty_rings(const CellGrid& g, CellValues& v, std::vector<float>& fit, int rings = 2);

// The volume's arrays from the values: fluence, flux, second moment and eq. MS-3's lobes
// (f_k = phi_k / phi, mu_k = their mean cosine to the sun, clamped to +-0.95); the fits when
// `fits`; l the light's propagation.
void pack_light_volume(const CellValues& v, std::vector<float>&& fit, bool fits, const glm::dvec3& l,
                       LightVolume& out);

}  // namespace nimbus::render::light_volume
