// Cloud fields: power-law layout and species templates (cloud_field.hpp).
#include "nimbus/volume/cloud_field.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <glm/common.hpp>

#include "nimbus/base/splitmix64.hpp"
#include "nimbus/volume/coverage_map.hpp"

namespace nimbus::volume {
namespace {

[[noreturn]] void bad(const std::string& what) { throw std::invalid_argument(what); }

using Rand = SplitMix64;  // layouts are the same on every platform

// Depth of a cloud of diameter L: about L (Stull, Practical Meteorology 6.6: cumulus depth about
// equal to diameter), capped by how high each species reaches above the base (humilis stop at
// the inversion a few hundred metres up, so large humilis are flat; congestus tower).
double cloud_depth(Species s, double L) {
  switch (s) {
    case Species::Humilis: return std::min(0.9 * L, 350.0);
    case Species::Mediocris: return std::min(1.0 * L, 1000.0);
    case Species::Congestus: return std::min(1.5 * L, 3500.0);
  }
  return L;
}

// log L with dn/dlog L ~ L^(-2b) on [log lo, log hi] by inverting its CDF (a = L^2, so
// dn/dlog a ~ a^-b).
double draw_log_diameter(double u, double b, double lo, double hi) {
  const double c = -2.0 * b, a0 = std::log(lo), a1 = std::log(hi);
  if (std::fabs(c) < 1e-9) return a0 + u * (a1 - a0);
  const double e0 = std::exp(c * a0), e1 = std::exp(c * a1);
  return std::log(e0 + u * (e1 - e0)) / c;
}

}  // namespace

const char* to_string(Species s) {
  switch (s) {
    case Species::Humilis: return "humilis";
    case Species::Mediocris: return "mediocris";
    case Species::Congestus: return "congestus";
  }
  return "?";
}

bool parse_species(const std::string& text, Species* out) {
  for (Species s : {Species::Humilis, Species::Mediocris, Species::Congestus})
    if (text == to_string(s)) {
      *out = s;
      return true;
    }
  return false;
}

void validate(const CloudFieldParams& p, const std::string& where) {
  auto need = [&](bool ok, const std::string& what) {
    if (!ok) bad(where + "." + what);
  };
  need(std::isfinite(p.center_m.x) && std::isfinite(p.center_m.y), "center must be finite (metres)");
  need(p.size_m.x > 0 && p.size_m.y > 0 && p.size_m.x <= 1e6 && p.size_m.y <= 1e6,
       "size must be in (0, 1e6] metres on both axes");
  need(p.coverage > 0 && p.coverage <= 0.9, "coverage must be in (0, 0.9]");
  need(p.size_exponent >= 0 && p.size_exponent <= 3, "size_exponent must be in [0, 3]");
  need(p.min_diameter_m >= 10 && std::isfinite(p.min_diameter_m), "min_diameter must be finite and >= 10 metres");
  need(p.max_diameter_m >= p.min_diameter_m && p.max_diameter_m <= 50000,
       "max_diameter must be in [min_diameter, 50000] metres");
  need(!p.species.empty(), "species: at least one species is needed");
  double total = 0.0;
  for (const SpeciesShare& s : p.species) {
    need(std::isfinite(s.share) && s.share >= 0, "species: shares must be finite and >= 0");
    total += s.share;
  }
  need(total > 0, "species: the shares must not all be 0");
  need(p.depth_scale > 0 && p.depth_scale <= 4, "depth_scale must be in (0, 4]");
  need(p.roughness >= 0 && p.roughness <= 1, "roughness must be in [0, 1]");
}

std::vector<FieldCloud> field_layout(const CloudFieldParams& p, const CoverageMap* map) {
  validate(p);
  Rand rng{0x243f6a8885a308d3ull ^ (uint64_t(p.seed) * 0x9e3779b97f4a7c15ull)};
  // The map's keep-or-reject draws come from a stream of their own, so that a map of 1
  // everywhere (every candidate kept) leaves the main stream, and the layout, as without a map.
  Rand keep_rng{0x13198a2e03707344ull ^ (uint64_t(p.seed) * 0xbf58476d1ce4e5b9ull)};
  const glm::dvec2 lo = p.center_m - 0.5 * p.size_m;
  // Diameters until their footprints (circles) reach the covered area; then the largest first.
  // A coverage map scales the area to cover by its mean over the field (1 for a white map).
  const double map_mean = map ? map->mean_over(lo, p.size_m) : 1.0;
  const double target = p.coverage * map_mean * p.size_m.x * p.size_m.y;
  // The mean footprint bounds the count before drawing: refuse runaway layouts by name.
  {
    double mean = 0.0;
    const int n = 4096;
    Rand probe{rng.state};
    for (int i = 0; i < n; ++i) {
      const double L = std::exp(draw_log_diameter(probe.uniform(), p.size_exponent, p.min_diameter_m, p.max_diameter_m));
      mean += std::numbers::pi / 4 * L * L / n;
    }
    if (target / mean > double(kMaxFieldClouds))
      bad("field: about " + std::to_string(int64_t(target / mean)) + " clouds would be placed (more than " +
          std::to_string(kMaxFieldClouds) + "): raise min_diameter or lower coverage or size");
  }
  std::vector<double> diam;
  double covered = 0.0;
  while (covered < target) {
    const double L = std::exp(draw_log_diameter(rng.uniform(), p.size_exponent, p.min_diameter_m, p.max_diameter_m));
    diam.push_back(L);
    covered += std::numbers::pi / 4 * L * L;
  }
  std::sort(diam.begin(), diam.end(), std::greater<>());
  double share_sum = 0.0;
  for (const SpeciesShare& s : p.species) share_sum += s.share;

  std::vector<FieldCloud> out;
  out.reserve(diam.size());
  // Placed clouds on a coarse bucket grid, to test "inside a bigger footprint" quickly. A periodic
  // field's buckets divide the period evenly, each at least a diameter wide, so that a wrapped
  // neighbour lies in the next bucket round.
  const double cell = std::max(p.max_diameter_m, 1.0);
  int nx = std::max(1, int(std::ceil(p.size_m.x / cell))), ny = std::max(1, int(std::ceil(p.size_m.y / cell)));
  glm::dvec2 cell2(cell);
  if (p.periodic) {
    nx = std::max(1, int(std::floor(p.size_m.x / cell)));
    ny = std::max(1, int(std::floor(p.size_m.y / cell)));
    cell2 = p.size_m / glm::dvec2(nx, ny);
  }
  std::vector<std::vector<uint32_t>> buckets(size_t(nx) * ny);
  auto bucket = [&](glm::dvec2 c, int dx, int dy) -> std::vector<uint32_t>* {
    int i = std::clamp(int((c.x - lo.x) / cell2.x), 0, nx - 1) + dx, j = std::clamp(int((c.y - lo.y) / cell2.y), 0, ny - 1) + dy;
    if (p.periodic) {
      i = (i % nx + nx) % nx;
      j = (j % ny + ny) % ny;
    }
    if (i < 0 || j < 0 || i >= nx || j >= ny) return nullptr;
    return &buckets[size_t(j) * nx + i];
  };
  // The offset between two centres; in a periodic field the shortest one round the period.
  auto offset = [&](glm::dvec2 a, glm::dvec2 b) {
    glm::dvec2 d = a - b;
    if (p.periodic) d -= p.size_m * glm::round(d / p.size_m);
    return d;
  };
  for (double L : diam) {
    FieldCloud c;
    c.diameter_m = L;
    bool placed = false;
    for (int attempt = 0; attempt < 32 && !placed; ++attempt) {
      c.center_m = lo + glm::dvec2(rng.uniform(), rng.uniform()) * p.size_m;
      // The map keeps the candidate with probability map(centre); a rejected one counts as a try.
      if (map && !(keep_rng.uniform() < map->at(c.center_m))) continue;
      bool overlaps = false;
      for (int dy = -1; dy <= 1 && !overlaps; ++dy)
        for (int dx = -1; dx <= 1 && !overlaps; ++dx)
          if (auto* b = bucket(c.center_m, dx, dy))
            for (uint32_t k : *b) {
              const glm::dvec2 d = offset(c.center_m, out[k].center_m);
              const double r = 0.5 * (out[k].diameter_m + L);
              if (d.x * d.x + d.y * d.y < r * r) {
                overlaps = true;
                break;
              }
            }
      placed = !overlaps;
    }
    // Every draw is made whether or not the cloud is kept, so the layout stays a pure function.
    const double species_u = rng.uniform(), depth_u = rng.uniform(0.8, 1.2);
    const uint32_t seed = static_cast<uint32_t>(rng.next() >> 32);
    if (!placed) continue;  // no room left for it: the field is as full as this size allows
    double u = species_u * share_sum;
    c.species = p.species.back().species;
    for (const SpeciesShare& s : p.species) {
      if (u < s.share) {
        c.species = s.species;
        break;
      }
      u -= s.share;
    }
    c.depth_m = cloud_depth(c.species, L) * p.depth_scale * depth_u;
    if (map && map->sets_height()) c.depth_m *= map->at(c.center_m);
    c.seed = seed;
    c.roughness = p.roughness;
    bucket(c.center_m, 0, 0)->push_back(static_cast<uint32_t>(out.size()));
    out.push_back(c);
  }
  return out;
}

std::vector<Shape> cloud_shapes(const FieldCloud& c, double base) {
  Rand rng{0x452821e638d01377ull ^ (uint64_t(c.seed) << 17) ^ c.seed};
  const double R = 0.5 * c.diameter_m, H = c.depth_m;
  std::vector<Shape> out;
  auto ellipsoid = [&](glm::dvec3 centre, glm::dvec3 size, double falloff) {
    Shape s;
    s.kind = ShapeKind::Ellipsoid;
    s.center = centre;
    s.size = size;
    s.falloff = falloff;
    s.roughness = c.roughness;
    s.roughness_seed = c.seed + static_cast<uint32_t>(out.size()) * 0x9e3779b9u;
    s.rooted = true;  // every part stands on the field's base
    s.root_z = base;
    out.push_back(s);
  };
  // The body: an ellipsoid standing on the base (rooted), which the model cuts flat.
  const double aspect = rng.uniform(0.75, 1.0), turn = rng.uniform(0.0, std::numbers::pi);
  const glm::dvec2 ax(std::cos(turn), std::sin(turn));
  const double rx = R * std::sqrt(aspect * 0.5 + 0.5), ry = R / std::sqrt(aspect * 0.5 + 0.5);
  // Axis-aligned ellipsoids only: the bounding box of a turned one would be loose, so the turn
  // goes into which axis is long.
  const bool x_long = std::fabs(ax.x) > std::fabs(ax.y);
  const glm::dvec3 body_size(x_long ? rx : ry, x_long ? ry : rx, 0.75 * H);
  ellipsoid({c.center_m.x, c.center_m.y, base + 0.25 * H}, body_size, 0.45);
  // Turrets: smaller ellipsoids rising from the body's top, off centre, tallest near the middle.
  const int turrets = c.species == Species::Humilis ? 1 : c.species == Species::Mediocris ? 3 : 5;
  for (int t = 0; t < turrets; ++t) {
    const double a = rng.uniform(0.0, 2 * std::numbers::pi), r = rng.uniform(0.0, 0.45) * R;
    const double size = R * rng.uniform(0.35, 0.55) * (c.species == Species::Congestus ? 0.8 : 1.0);
    const double rise = c.species == Species::Humilis ? 0.55 : rng.uniform(0.45, 0.75);
    const glm::dvec3 centre(c.center_m.x + r * std::cos(a), c.center_m.y + r * std::sin(a), base + rise * H);
    const double top = base + H - centre.z;  // the turret reaches the cloud's top
    ellipsoid(centre, {size, size, std::max(0.3 * size, std::min(top, 0.5 * H))}, 0.5);
  }
  return out;
}

std::vector<Shape> field_shapes(const CloudFieldParams& p, double base, const CoverageMap* map) {
  std::vector<Shape> out;
  for (const FieldCloud& c : field_layout(p, map)) {
    if (!(c.depth_m > 0.0)) continue;  // a map value of 0 (height) leaves no cloud
    const std::vector<Shape> s = cloud_shapes(c, base);
    out.insert(out.end(), s.begin(), s.end());
  }
  return out;
}

}  // namespace nimbus::volume
