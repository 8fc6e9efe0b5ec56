// Observational cloud statistics on optical-depth maps:
// Lovejoy 1982 (perimeter-area dimension), DeWitt et al. 2024 and DeWitt & Garrett 2024 (area
// distribution, bins under 24 counts dropped), Cahalan & Snider 1989 (1-D spectra of tau).
#include "support/cloud_stats.hpp"

#include <kissfft.hh>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include "nimbus/base/memory.hpp"
#include "nimbus/base/validate.hpp"

namespace nimbus::test {
namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// The voxel size h of a transform whose index axes map to world axes as h * identity (a
// uniform scale plus a translation); throws otherwise.
double uniform_axis_aligned_voxel_m(const openvdb::math::Transform& xf) {
  require(xf.isLinear(), "density: its transform is not linear (a frustum?); vertical columns need a uniform scale");
  const openvdb::math::MapBase::ConstPtr map = xf.baseMap();
  const openvdb::Vec3d ex = map->applyJacobian(openvdb::Vec3d(1, 0, 0));
  const openvdb::Vec3d ey = map->applyJacobian(openvdb::Vec3d(0, 1, 0));
  const openvdb::Vec3d ez = map->applyJacobian(openvdb::Vec3d(0, 0, 1));
  const double h = ex.x();
  const double tol = 1e-9 * std::abs(h);
  const bool ok = std::isfinite(h) && h > 0 && (ex - openvdb::Vec3d(h, 0, 0)).length() <= tol &&
                  (ey - openvdb::Vec3d(0, h, 0)).length() <= tol && (ez - openvdb::Vec3d(0, 0, h)).length() <= tol;
  require(ok, "density: its transform must be a uniform, axis-aligned scale (cubic voxels, index z up); index "
              "axes map to (" + num(ex.x()) + ", " + num(ex.y()) + ", " + num(ex.z()) + "), (" + num(ey.x()) + ", " +
              num(ey.y()) + ", " + num(ey.z()) + "), (" + num(ez.x()) + ", " + num(ez.y()) + ", " + num(ez.z()) + ")");
  return h;
}

void check_map(const OpticalDepthMap& m) {
  require(m.nx > 0 && m.ny > 0, "map: empty (" + std::to_string(m.nx) + " x " + std::to_string(m.ny) + " pixels)");
  require(m.tau.size() == size_t(m.nx) * size_t(m.ny),
          "map: tau holds " + std::to_string(m.tau.size()) + " values, not nx * ny = " + std::to_string(m.nx) + " * " +
              std::to_string(m.ny));
  require(std::isfinite(m.pixel_m) && m.pixel_m > 0,
          "map: pixel_m must be finite and positive (got " + num(m.pixel_m) + ")");
}

// Ordinary least squares y = slope x + c; the slope's standard error is
// sqrt(sum r^2 / (n - 2) / Sxx), +infinity for n = 2 (no residual degree of freedom).
struct Line {
  double slope = 0, slope_se = 0;
};

Line least_squares(const std::vector<double>& x, const std::vector<double>& y, const std::string& what) {
  const size_t n = x.size();
  require(n >= 2, what + ": " + std::to_string(n) + " usable point(s), a fit needs at least 2");
  double mx = 0, my = 0;
  for (size_t i = 0; i < n; ++i) {
    mx += x[i];
    my += y[i];
  }
  mx /= double(n);
  my /= double(n);
  double sxx = 0, sxy = 0;
  for (size_t i = 0; i < n; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  require(sxx > 0, what + ": every point has the same abscissa, the slope is undefined");
  Line l;
  l.slope = sxy / sxx;
  if (n == 2) {
    l.slope_se = std::numeric_limits<double>::infinity();
  } else {
    double ssr = 0;
    for (size_t i = 0; i < n; ++i) {
      const double r = y[i] - my - l.slope * (x[i] - mx);
      ssr += r * r;
    }
    l.slope_se = std::sqrt(ssr / double(n - 2) / sxx);
  }
  return l;
}

// The clouds the fits use: whole ones (edge-truncated clouds bias the exponents, DeWitt & Garrett
// 2024) of at least min_pixels pixels.
bool enters_fit(const CloudOutline& c, int64_t min_pixels) { return !c.touches_edge && c.pixels >= min_pixels; }

}  // namespace

OpticalDepthMap vertical_optical_depth(const openvdb::FloatGrid& density, double extinction_per_m,
                                       const openvdb::CoordBBox& columns) {
  require(std::isfinite(extinction_per_m) && extinction_per_m > 0,
          "extinction_per_m must be finite and positive (got " + num(extinction_per_m) + ")");
  require(!columns.empty(), "columns: the box is empty");
  const double h = uniform_axis_aligned_voxel_m(density.transform());
  require(density.background() == 0.0f,
          "density: background " + num(density.background()) + " is not 0; an inactive column would have infinite tau");
  const openvdb::Coord lo = columns.min(), hi = columns.max();
  const int64_t nx = int64_t(hi.x()) - lo.x() + 1, ny = int64_t(hi.y()) - lo.y() + 1;
  require(nx <= kMaxOpticalDepthPixels && ny <= kMaxOpticalDepthPixels && nx * ny <= kMaxOpticalDepthPixels,
          "columns: " + std::to_string(nx) + " x " + std::to_string(ny) + " is over the map limit of " +
              std::to_string(kMaxOpticalDepthPixels) + " pixels");
  ensure_fits_in_memory(uint64_t(nx * ny), sizeof(double), "an optical-depth map");

  OpticalDepthMap m;
  m.nx = int(nx);
  m.ny = int(ny);
  m.pixel_m = h;
  m.tau.assign(size_t(nx * ny), 0.0);
  // Column sums of the active values; a tile adds its value once per voxel of its z extent.
  for (auto it = density.cbeginValueOn(); it; ++it) {
    openvdb::CoordBBox b;
    it.getBoundingBox(b);
    const int x0 = std::max(b.min().x(), lo.x()), x1 = std::min(b.max().x(), hi.x());
    const int y0 = std::max(b.min().y(), lo.y()), y1 = std::min(b.max().y(), hi.y());
    if (x0 > x1 || y0 > y1) continue;
    const double column_sum = double(*it) * double(int64_t(b.max().z()) - b.min().z() + 1);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) m.tau[size_t(y - lo.y()) * size_t(nx) + size_t(x - lo.x())] += column_sum;
  }
  const double scale = extinction_per_m * h;
  for (size_t p = 0; p < m.tau.size(); ++p) {
    m.tau[p] *= scale;
    if (!std::isfinite(m.tau[p]))
      throw std::invalid_argument("density: column (" + std::to_string(lo.x() + int64_t(p % size_t(nx))) + ", " +
                                  std::to_string(lo.y() + int64_t(p / size_t(nx))) +
                                  ") has a non-finite optical depth (non-finite or huge densities)");
  }
  return m;
}

std::vector<CloudOutline> cloud_outlines(const OpticalDepthMap& m, double threshold) {
  check_map(m);
  require(std::isfinite(threshold), "threshold must be finite (got " + num(threshold) + ")");
  const int nx = m.nx, ny = m.ny;
  const size_t n = m.tau.size();
  ensure_fits_in_memory(n, 1, "the cloud mask of a " + std::to_string(nx) + " x " + std::to_string(ny) + " map");
  // 0: clear, 1: cloud not yet labelled, 2: cloud labelled.
  std::vector<uint8_t> state(n);
  for (size_t p = 0; p < n; ++p) {
    if (std::isnan(m.tau[p]))
      throw std::invalid_argument("map: tau is NaN at pixel (" + std::to_string(p % size_t(nx)) + ", " +
                                  std::to_string(p / size_t(nx)) + ")");
    state[p] = m.tau[p] >= threshold ? 1 : 0;
  }
  auto at = [&](int i, int j) -> uint8_t& { return state[size_t(j) * size_t(nx) + size_t(i)]; };
  auto clear = [&](int i, int j) { return i < 0 || j < 0 || i >= nx || j >= ny || at(i, j) == 0; };

  std::vector<CloudOutline> clouds;
  std::vector<std::pair<int, int>> seeds;  // span fill: one seed per run still to label
  for (int j0 = 0; j0 < ny; ++j0)
    for (int i0 = 0; i0 < nx; ++i0) {
      if (at(i0, j0) != 1) continue;
      int64_t pixels = 0, edges = 0;
      bool edge = false;
      seeds.assign(1, {i0, j0});
      while (!seeds.empty()) {
        const auto [i, j] = seeds.back();
        seeds.pop_back();
        if (at(i, j) != 1) continue;
        int l = i, r = i;
        while (l > 0 && at(l - 1, j) == 1) --l;
        while (r < nx - 1 && at(r + 1, j) == 1) ++r;
        for (int k = l; k <= r; ++k) {
          at(k, j) = 2;
          edges += int(clear(k - 1, j)) + int(clear(k + 1, j)) + int(clear(k, j - 1)) + int(clear(k, j + 1));
        }
        pixels += r - l + 1;
        edge |= j == 0 || j == ny - 1 || l == 0 || r == nx - 1;
        for (const int jj : {j - 1, j + 1}) {
          if (jj < 0 || jj >= ny) continue;
          for (int k = l; k <= r; ++k)
            if (at(k, jj) == 1 && (k == l || at(k - 1, jj) != 1)) seeds.emplace_back(k, jj);
        }
      }
      clouds.push_back({pixels, double(pixels) * m.pixel_m * m.pixel_m, double(edges) * m.pixel_m, edge});
    }
  return clouds;
}

PowerLawFit perimeter_area_dimension(const std::vector<CloudOutline>& clouds, int64_t min_pixels) {
  require(min_pixels >= 1, "min_pixels must be at least 1 (got " + std::to_string(min_pixels) + ")");
  // Lovejoy 1982: P ∝ sqrt(A)^D, so D is the slope of log P against log sqrt(A).
  std::vector<double> log_root_a, log_p;
  PowerLawFit fit;
  fit.x_lo = std::numeric_limits<double>::infinity();
  for (const CloudOutline& c : clouds) {
    if (!enters_fit(c, min_pixels)) continue;
    if (!(std::isfinite(c.area_m2) && c.area_m2 > 0 && std::isfinite(c.perimeter_m) && c.perimeter_m > 0))
      throw std::invalid_argument("clouds: a cloud of " + std::to_string(c.pixels) + " pixels has area " +
                                  num(c.area_m2) + " m^2 and perimeter " + num(c.perimeter_m) +
                                  " m; both must be finite and positive");
    const double root_a = std::sqrt(c.area_m2);
    log_root_a.push_back(std::log10(root_a));
    log_p.push_back(std::log10(c.perimeter_m));
    fit.x_lo = std::min(fit.x_lo, root_a);
    fit.x_hi = std::max(fit.x_hi, root_a);
  }
  const Line l = least_squares(log_root_a, log_p,
                               "clouds (not touching the edge, at least " + std::to_string(min_pixels) + " pixels)");
  fit.exponent = l.slope;
  fit.standard_error = l.slope_se;
  fit.points = int(log_p.size());
  return fit;
}

PowerLawFit area_exponent(const std::vector<CloudOutline>& clouds, int bins_per_decade, int min_count,
                          int64_t min_pixels) {
  require(bins_per_decade >= 1 && bins_per_decade <= 100,
          "bins_per_decade must be in [1, 100] (got " + std::to_string(bins_per_decade) + ")");
  require(min_count >= 1, "min_count must be at least 1 (got " + std::to_string(min_count) + ")");
  require(min_pixels >= 1, "min_pixels must be at least 1 (got " + std::to_string(min_pixels) + ")");
  // Bin n holds areas in [10^(n / bpd), 10^((n + 1) / bpd)).
  const double bpd = bins_per_decade;
  std::map<int64_t, int64_t> count;
  for (const CloudOutline& c : clouds) {
    if (!enters_fit(c, min_pixels)) continue;
    if (!(std::isfinite(c.area_m2) && c.area_m2 > 0))
      throw std::invalid_argument("clouds: a cloud of " + std::to_string(c.pixels) + " pixels has area " +
                                  num(c.area_m2) + " m^2; it must be finite and positive");
    ++count[int64_t(std::floor(std::log10(c.area_m2) * bpd))];
  }
  // dn/dlog a = count / (1 / bpd); bins under min_count dropped (DeWitt & Garrett 2024).
  std::vector<double> log_a, log_dn;
  PowerLawFit fit;
  for (const auto& [bin, n] : count) {
    if (n < min_count) continue;
    const double log_centre = (double(bin) + 0.5) / bpd;
    log_a.push_back(log_centre);
    log_dn.push_back(std::log10(double(n) * bpd));
    if (log_a.size() == 1) fit.x_lo = std::pow(10.0, log_centre);
    fit.x_hi = std::pow(10.0, log_centre);
  }
  const Line l = least_squares(
      log_a, log_dn, "area bins (with at least " + std::to_string(min_count) + " clouds not touching the edge)");
  fit.exponent = -l.slope;
  fit.standard_error = l.slope_se;
  fit.points = int(log_a.size());
  return fit;
}

PowerLawFit spectrum_slope(const OpticalDepthMap& m, MapAxis along, double lambda_lo_m, double lambda_hi_m) {
  check_map(m);
  const bool x = along == MapAxis::X;
  const int n = x ? m.nx : m.ny, lines = x ? m.ny : m.nx;
  const double length_m = n * m.pixel_m;
  const std::string axis = x ? "x" : "y";
  require(std::isfinite(lambda_lo_m) && std::isfinite(lambda_hi_m) && lambda_lo_m > 0 && lambda_lo_m < lambda_hi_m,
          "lambda_lo_m and lambda_hi_m must be finite with 0 < lambda_lo_m < lambda_hi_m (got " + num(lambda_lo_m) +
              ", " + num(lambda_hi_m) + ")");
  require(lambda_lo_m >= 2 * m.pixel_m, "lambda_lo_m " + num(lambda_lo_m) + " is under the Nyquist wavelength " +
                                            num(2 * m.pixel_m) + " m (2 pixels)");
  require(lambda_hi_m <= length_m, "lambda_hi_m " + num(lambda_hi_m) + " is over the line length along " + axis +
                                       ", " + num(length_m) + " m");
  for (size_t p = 0; p < m.tau.size(); ++p)
    if (!std::isfinite(m.tau[p]))
      throw std::invalid_argument("map: tau is not finite at pixel (" + std::to_string(p % size_t(m.nx)) + ", " +
                                  std::to_string(p / size_t(m.nx)) + ")");

  // Mean removed, periodic Hann window, |FFT|^2 averaged over the lines.
  const size_t len = static_cast<size_t>(n);
  std::vector<double> hann(len);
  for (int i = 0; i < n; ++i) hann[size_t(i)] = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * i / n);
  const kissfft<double> fft(len, false);
  std::vector<std::complex<double>> line(len), spectrum(len);
  std::vector<double> power(size_t(n / 2 + 1), 0.0);
  for (int l = 0; l < lines; ++l) {
    auto tau = [&](int i) { return x ? m.at(i, l) : m.at(l, i); };
    double mean = 0, lo = tau(0), hi = tau(0);
    for (int i = 0; i < n; ++i) {
      mean += tau(i);
      lo = std::min(lo, tau(i));
      hi = std::max(hi, tau(i));
    }
    if (lo == hi) continue;  // a constant line has no power (its rounded mean would leave some)
    mean /= n;
    for (int i = 0; i < n; ++i) line[size_t(i)] = (tau(i) - mean) * hann[size_t(i)];
    fft.transform(line.data(), spectrum.data());
    for (int k = 1; k <= n / 2; ++k) power[size_t(k)] += std::norm(spectrum[size_t(k)]);
  }
  for (double& p : power) p /= lines;

  // k = mode / length_m in cycles per metre; 10 log-spaced bins a decade, one point each.
  constexpr double kBinsPerDecade = 10;
  const double k_lo = 1 / lambda_hi_m * (1 - 1e-12), k_hi = 1 / lambda_lo_m * (1 + 1e-12);
  struct Bin {
    double power = 0, log_k = 0;
    int modes = 0;
  };
  std::map<int64_t, Bin> bins;
  for (int mode = 1; mode <= n / 2; ++mode) {
    const double k = mode / length_m;
    if (k < k_lo || k > k_hi) continue;
    Bin& b = bins[int64_t(std::floor(std::log10(k) * kBinsPerDecade))];
    b.power += power[size_t(mode)];
    b.log_k += std::log10(k);
    ++b.modes;
  }
  std::vector<double> log_k, log_p;
  PowerLawFit fit;
  for (const auto& [index, b] : bins) {
    const double mean_log_k = b.log_k / b.modes, mean_power = b.power / b.modes;
    require(mean_power > 0, "map: no power along " + axis + " at wavelength " + num(std::pow(10.0, -mean_log_k)) +
                                " m (tau does not vary along the lines there)");
    log_k.push_back(mean_log_k);
    log_p.push_back(std::log10(mean_power));
    if (log_k.size() == 1) fit.x_lo = std::pow(10.0, mean_log_k);
    fit.x_hi = std::pow(10.0, mean_log_k);
  }
  const Line l = least_squares(log_k, log_p,
                               "wavenumber bins between " + num(lambda_lo_m) + " m and " + num(lambda_hi_m) + " m");
  fit.exponent = l.slope;
  fit.standard_error = l.slope_se;
  fit.points = int(log_k.size());
  return fit;
}

}  // namespace nimbus::test
