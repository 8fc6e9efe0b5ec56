// The sky scene's ground albedo texture and its CPU read (ground_albedo.hpp).
#include "nimbus/render/scene/ground_albedo.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <span>
#include <stdexcept>
#include <string>

#include "nimbus/noise/batch.hpp"
#include "nimbus/noise/field.hpp"

namespace nimbus::render {
namespace glsl {
using namespace glm;
#include "lib/ground_albedo_map.glsl"
}  // namespace glsl

namespace {

// Land-use colours, linear albedo (ground_albedo.hpp: luminances within Oke's table 2.1).
constexpr glm::dvec3 kWoods{0.045, 0.075, 0.03};   // luminance 0.066 (coniferous 0.05-0.15)
constexpr glm::dvec3 kMeadow{0.10, 0.17, 0.06};    // 0.148 (grass 0.16-0.26 broadband; less in the visible)
constexpr glm::dvec3 kCrops{0.21, 0.20, 0.10};     // 0.195 (crops 0.18-0.25)
constexpr glm::dvec3 kSoil{0.23, 0.165, 0.10};     // 0.174 (soils 0.05-0.40)

double luminance(const glm::dvec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

double smoothstep(double a, double b, double x) {
  const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// A periodic gradient fBm over the texture: `cells` lattice cells per period, `octaves`
// octaves (lacunarity 2, so the sum stays periodic), sampled at the texel centres.
std::vector<float> periodic_fbm(int size, int cells, int octaves, unsigned seed) {
  noise::NoiseParams p;
  p.kind = noise::Kind::Gradient;
  p.fractal = octaves > 1 ? noise::Fractal::Fbm : noise::Fractal::None;
  p.octaves = octaves;
  p.frequency = cells;  // lattice cells per texture period (input unit)
  p.seed = seed;
  p.period = {cells, cells, 0};
  noise::GridSpec g;
  g.origin = {0.5 / size, 0.5 / size, 0.0};
  g.spacing = 1.0 / size;
  g.res = {size, size, 1};
  std::vector<float> out(static_cast<std::size_t>(size) * size);
  noise::evaluate_grid(noise::NoiseField(p), g, out);
  return out;
}

void check(const GroundAlbedoParams& p) {
  const auto bad = [](const std::string& what) { throw std::invalid_argument("ground albedo " + what); };
  if (p.size < 16 || p.size > 4096 || (p.size & (p.size - 1)) != 0) bad("size: must be a power of two in [16, 4096]");
  if (!(std::isfinite(p.period_m) && p.period_m > 0.0)) bad("period_m: must be finite and > 0");
  if (!(std::isfinite(p.detail_period_m) && p.detail_period_m > 0.0)) bad("detail_period_m: must be finite and > 0");
  if (!(p.detail_strength >= 0.0 && p.detail_strength < 1.0)) bad("detail_strength: must be in [0, 1)");
}

// Bilinear read of one level, repeating, texel centres at (i + 1/2) / size (GL_LINEAR, GL_REPEAT).
glm::dvec3 bilinear(const GroundAlbedoTexture& t, int level, glm::dvec2 uv) {
  const int n = t.size(level);
  const std::vector<glm::vec3>& tex = t.levels[static_cast<std::size_t>(level)];
  const double x = (uv.x - std::floor(uv.x)) * n - 0.5, y = (uv.y - std::floor(uv.y)) * n - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const double wx = x - fx, wy = y - fy;
  const auto wrap = [n](double i) { return static_cast<std::size_t>(((static_cast<long>(i) % n) + n) % n); };
  const std::size_t x0 = wrap(fx), x1 = wrap(fx + 1), y0 = wrap(fy), y1 = wrap(fy + 1);
  const auto at = [&](std::size_t i, std::size_t j) { return glm::dvec3(tex[j * n + i]); };
  return (1 - wy) * ((1 - wx) * at(x0, y0) + wx * at(x1, y0)) + wy * ((1 - wx) * at(x0, y1) + wx * at(x1, y1));
}

}  // namespace

std::shared_ptr<const GroundAlbedoTexture> bake_ground_albedo(const GroundAlbedoParams& params) {
  check(params);
  const int n = params.size;
  // The land use: one fBm picks woods, meadow or crops (a few patches a kilometre across), a
  // second, coarser one where crops give way to bare soil; a fine one varies the brightness
  // within each patch (texel to texel, about 12 m at the sky scene's period).
  const std::vector<float> use = periodic_fbm(n, 8, 6, params.seed);
  const std::vector<float> dry = periodic_fbm(n, 4, 4, params.seed + 1);
  const std::vector<float> fine = periodic_fbm(n, 64, 3, params.seed + 2);
  auto tex = std::make_shared<GroundAlbedoTexture>();
  tex->params = params;
  tex->levels.emplace_back(static_cast<std::size_t>(n) * n);
  tbb::parallel_for(0, n, [&](int j) {
    for (int i = 0; i < n; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * n + i;
      const double s = use[k], d = dry[k];
      glm::dvec3 c = glm::mix(kMeadow, glm::mix(kCrops, kSoil, smoothstep(0.05, 0.2, d)), smoothstep(0.04, 0.12, s));
      c = glm::mix(c, kWoods, smoothstep(-0.14, -0.22, s));
      c *= 1.0 + params.detail_strength * fine[k];
      tex->levels[0][k] = glm::vec3(glm::clamp(c, 0.0, 1.0));
    }
  });
  for (int size = n / 2; size >= 1; size /= 2) {
    const std::vector<glm::vec3>& up = tex->levels.back();
    std::vector<glm::vec3> down(static_cast<std::size_t>(size) * size);
    for (int j = 0; j < size; ++j)
      for (int i = 0; i < size; ++i) {
        const std::size_t a = static_cast<std::size_t>(2 * j) * (2 * size) + 2 * i, b = a + 2 * size;
        down[static_cast<std::size_t>(j) * size + i] = 0.25f * (up[a] + up[a + 1] + up[b] + up[b + 1]);
      }
    tex->levels.push_back(std::move(down));
  }
  glm::dvec3 sum(0.0);
  for (const glm::vec3& c : tex->levels[0]) sum += glm::dvec3(c);
  tex->mean = sum / static_cast<double>(tex->levels[0].size());
  tex->mean_luminance = luminance(tex->mean);
  return tex;
}

std::shared_ptr<const GroundAlbedoTexture> sky_ground_albedo() {
  static std::once_flag once;
  static std::shared_ptr<const GroundAlbedoTexture> tex;
  std::call_once(once, [] { tex = bake_ground_albedo(GroundAlbedoParams{}); });
  return tex;
}

glm::dvec3 sample_ground_texture(const GroundAlbedoTexture& t, glm::dvec2 uv, double lod) {
  const double l = std::clamp(lod, 0.0, static_cast<double>(t.level_count() - 1));
  const int l0 = static_cast<int>(std::floor(l));
  const int l1 = std::min(l0 + 1, t.level_count() - 1);
  const double w = l - l0;
  const glm::dvec3 a = bilinear(t, l0, uv);
  return w > 0.0 ? glm::mix(a, bilinear(t, l1, uv), w) : a;
}

glm::dvec3 ground_albedo(const GroundAlbedoTexture& t, double x_m, double z_m, const glm::dvec3& dir,
                         double distance_m, double pixel_angle_rad) {
  const glm::vec2 fp = glsl::ground_footprint(static_cast<float>(dir.y), static_cast<float>(distance_m),
                                              static_cast<float>(pixel_angle_rad));
  const glm::dvec2 h = glm::length(glm::dvec2(dir.x, dir.z)) > 1e-12 ? glm::normalize(glm::dvec2(dir.x, dir.z)) : glm::dvec2(1.0, 0.0);
  const double texels = t.params.size;
  const double lod_land = glsl::ground_lod(fp, static_cast<float>(t.params.period_m / texels));
  const double lod_detail = glsl::ground_lod(fp, static_cast<float>(t.params.detail_period_m / texels));
  glm::dvec3 land(0.0), detail(0.0);
  for (int k = 0; k < glsl::GROUND_TAPS; ++k) {
    const glm::dvec2 p = glm::dvec2(x_m, z_m) + h * static_cast<double>(glsl::ground_tap_offset(k, fp.y));
    land += sample_ground_texture(t, p / t.params.period_m, lod_land);
    detail += sample_ground_texture(t, p / t.params.detail_period_m, lod_detail);
  }
  land /= glsl::GROUND_TAPS;
  detail /= glsl::GROUND_TAPS;
  return glm::dvec3(glsl::ground_combine(glm::vec3(land), glm::vec3(detail), static_cast<float>(t.mean_luminance)));
}

}  // namespace nimbus::render
