// The density field of a cloud or gas: shapes that place it, noise that gives it billows and
// wisps, and Ebert's gas function that turns the result into density (Ebert et al. 2003, as in Hoffmann 2007). Z is up,
// units are metres and seconds.
//
//   q0     = p - wind t - (shear_x, shear_y, 0) (z - base)          leaning with height
//   q      = q0 + displacement * (fbm_x, fbm_y, fbm_z)(q0)   at most displacement metres long
//   n      = q squeezed by 1/stretch along stretch_direction above stretch_altitude (noise)
//   s      = max over shapes of coverage(q) * ceiling(q0.z) * base(q0.z)   in [0, 1]
//   w      = calm(q0.z): 0 at the base and the ceiling, 1 flat_layer metres from them
//   z      = (fbm(q) - mean(fbm)) / sd(fbm)                        zero mean, unit variance
//   z'     = w z + (1 - w) kBaseBillow                              the noise, calmed
//   f      = s (1 + billow z') - (1 - coverage) - w (erosion * turbulence_detail(n)
//            + furrows * ridged(n) + cauliflower * (1 - perlin_worley(n)))
//   density = gas(f) = pow(f * max_density, exponent)  (0 where f <= 0)
// The base and the ceiling are level in q0 (not moved by the displacement), and the noise is
// calmed next to them: a cumulus base is the condensation level and an anvil's top the
// tropopause, both flat; the turbulence shapes the walls and the top (docs/volume.md). At the
// base the cloud fills what the billows reach 1.5 standard deviations up (kBaseBillow), so
// nearly every column that holds cloud above holds it at the base too.
// The noise modulates the coverage, so the density is exactly 0 outside the shapes and
// continuous at their boundary; since fbm <= 1, f can be positive only where
// s > (1 - coverage) / (1 + billow (1 - mean) / sd(fbm)), and the noise is evaluated only there.
// ridged = sum a_i (1 - |n_i|)^2 / sum a_i peaks sharply where the noise crosses zero (the
// cumulonimbus of Hoffmann 2007: turbulence "folded at the middle"), so subtracting it cuts deep, narrow
// furrows between large smooth lumps; it is in [0, 1] and only lowers f, so the bound holds.
#pragma once
#include <array>
#include <cstdint>
#include <glm/vec3.hpp>
#include <memory>
#include <string>
#include <vector>

#include <optional>

#include <glm/vec2.hpp>

#include "nimbus/noise/field.hpp"
#include "nimbus/noise/perlin_worley.hpp"
#include "nimbus/volume/cloud_field.hpp"
#include "nimbus/volume/coverage_map.hpp"
#include "nimbus/volume/gas.hpp"
#include "nimbus/volume/shape.hpp"
#include "nimbus/volume/shape_index.hpp"

namespace nimbus::volume {

// The calmed billow noise at the base and the ceiling, in standard deviations (see above).
inline constexpr double kBaseBillow = 1.5;

struct CloudParams {
  std::vector<Shape> shapes;
  // Many clouds (cloud_field.hpp): the field's shapes join `shapes`, on base_altitude.
  std::optional<CloudFieldParams> field;
  // Cloud base: coverage rises from 0 at base_altitude to full at base_altitude +
  // base_softness (metres, along z), which flattens the base as convection does.
  double base_altitude = -1e30;
  double base_softness = 50.0;
  // Ceiling (the tropopause, where a cumulonimbus spreads into its anvil): coverage falls from
  // full at ceiling_altitude - ceiling_softness to 0 at ceiling_altitude (metres), except in
  // shapes marked `overshoot`. Default: none.
  double ceiling_altitude = 1e30;
  double ceiling_softness = 100.0;
  // Metres above the base (and below the ceiling) over which the noise grows from calm (w = 0)
  // to its full amplitude, so the base (and the ceiling) stay flat. 0: full noise everywhere.
  double flat_layer = 0.0;
  noise::Kind noise = noise::Kind::Gradient;  // billow noise kind
  double frequency = 1.0 / 400.0;    // billow noise, cycles per metre (first octave)
  int octaves = 6;                   // at most; fewer where the voxel cannot resolve them
  double lacunarity = 2.0;
  double gain = 0.5;
  double coverage = 0.5;             // [0, 1]: how much of the shapes' volume holds cloud
  double billow = 0.35;              // noise amplitude, in coverage units per noise sd
  double erosion = 0.0;              // [0, 1]: detail turbulence eaten from the field
  double erosion_frequency = 1.0 / 60.0;  // cycles per metre
  double furrows = 0.0;              // [0, 1]: ridged noise subtracted (cumulonimbus furrows); 0: none
  double furrow_frequency = 1.0 / 1500.0;  // cycles per metre; lumps are about half a cycle across
  double displacement = 0.0;         // metres: turbulent displacement of the coordinates
  double displacement_frequency = 1.0 / 800.0;  // cycles per metre
  // Cauliflower billows: the gaps of Perlin-Worley noise (round Worley cells filled by Perlin
  // fBm, noise/perlin_worley.hpp) carved from the surface, so it bulges in lumps on lumps. [0, 1]
  double cauliflower = 0.0;
  double cauliflower_frequency = 1.0 / 150.0;  // cycles per metre: lumps about 1/f across
  // Fibres: the noise squeezed by 1/stretch along stretch_direction (horizontal, x and y;
  // normalised on use), so its features are stretch times longer that way (presets point it
  // along their upper wind); above stretch_altitude (metres), blended in over 200 m. stretch 1:
  // none. [1, 64]. A parameter rather than the wind, so that a cloud without drift (the wind
  // applied at render time, as the viewer's sky does) keeps its fibres.
  double stretch = 1.0;
  double stretch_altitude = -1e30;
  glm::dvec2 stretch_direction{1.0, 0.0};
  // Wind shear: metres of horizontal lean per metre above base_altitude (0 when the base is
  // unset), x and y. Tops lean downwind.
  glm::dvec2 shear{0.0};
  GasParams gas;
  glm::dvec3 wind{0.0};              // metres per second
  double evolution = 0.0;            // noise lattice units per second (boiling); 0: static
  uint32_t seed = 0;
  // Hot gases (smoke, steam): a temperature grid on the density's voxels, 1 at
  // temperature_base and cooling linearly to 0 over temperature_height metres above it
  // (Blender reads 0..1 as 0..1000 K). temperature_height 0: no temperature grid.
  double temperature_base = 0.0;
  double temperature_height = 0.0;
  // A sky without edges (docs/volume.md, "Periodic fields"): the density repeats with this period
  // in x and y, metres ((0, 0): not periodic), over a tile centred on the origin; a periodic field
  // (field.periodic) sets it to the field's size, centred on the field. Every noise gets a whole
  // number of cycles per period: its frequency becomes round(period * frequency) / period (at
  // least one cycle). Shapes crossing the tile's edges are replicated across the opposite ones,
  // and a slab at least a period wide is endless along that axis.
  glm::dvec2 period_m{0.0};
  // Coverage (weather) map (coverage_map.hpp): a PNG whose red channel multiplies the shapes'
  // coverage (0: no cloud) at the point moved back by the wind (the map travels with the clouds);
  // a field also keeps each cloud's centre with probability map(centre). Empty: none.
  std::string coverage_map;
  // The map's pixels: read from coverage_map by cloud_from_json, or given in memory.
  std::shared_ptr<const CoverageImage> coverage_image;
  // West, south, east, north (metres) the map is stretched over; all 0: the field's area, else
  // the periodic tile, else the shapes' horizontal bounds.
  std::array<double, 4> coverage_map_extent{0.0, 0.0, 0.0, 0.0};
  bool coverage_map_height = false;  // the map also multiplies each field cloud's depth
};

// The periodic tile of the parameters (lo corner and size, metres), or nothing when they are not
// periodic.
struct PeriodicTile {
  glm::dvec2 lo_m{0.0}, size_m{0.0};
};
std::optional<PeriodicTile> periodic_tile(const CloudParams& p);
// The VDB metadata key in which `nimbus generate` writes a periodic tile's size, "PX PY" (metres,
// the world's x and y), so that renderers can draw its copies (render/core cloud_source.hpp).
inline constexpr const char* kPeriodMetadataKey = "period_m";

// Throws std::invalid_argument naming the parameter.
void validate(const CloudParams& p);

// One cloud at one time, with noise octaves limited to what `voxel_size` can resolve.
class CloudModel {
 public:
  CloudModel(const CloudParams& params, double voxel_size, double time_seconds);

  const CloudParams& params() const { return params_; }
  double time() const { return time_; }

  // Density at a world point (scalar path).
  float density(const glm::dvec3& p) const;

  // Where density can be non-zero (shapes, moved by the wind and the shear, grown by the
  // displacement).
  Aabb bounds() const;
  // Whether any point of the world box may have non-zero density.
  bool may_touch(const Aabb& world_box) const;
  // Every shape: the explicit ones, then the field's (then, periodic, the replicas).
  const std::vector<Shape>& shapes() const { return shapes_; }
  // The periodic tile, if any; bounds() spans exactly it in x and y.
  const std::optional<PeriodicTile>& tile() const { return tile_; }
  // The coverage map's value at a world point at this model's time (1 without a map).
  double map_at(const glm::dvec3& p) const;

  // The coverage at or below which f cannot become positive whatever the noise.
  double min_useful_coverage() const { return min_useful_coverage_; }

  // Octaves of the billow noise kept / asked for.
  int octaves_used() const;

  // Batched: densities at n points (world metres), noise through the SIMD batch path. Points
  // whose coverage is below min_useful_coverage() cost no noise evaluation, and those whose
  // billow noise leaves no density (unbitten) none of the other noises. Returns how many
  // points needed the billow noise.
  // `far`, when not null, holds n flags: which points no displacement moves into a shape (their
  // density is 0). With far_known they are read from it (found at another time: they do not
  // depend on time when the wind is 0), else they are found and written to it.
  int64_t densities(const glm::dvec3* points, size_t n, float* out, uint8_t* far = nullptr, bool far_known = false) const;
  // The inputs the far test depends on besides the points: the shapes, the displacement, the
  // wind's drift at this time, the shear and the periodic tile, as numbers (GenerationReuse::key).
  std::vector<double> far_test_key() const;

 private:
  glm::dvec3 sheared(const glm::dvec3& p) const;  // q0: wind and shear applied
  glm::dvec3 moved(const glm::dvec3& p) const;    // q: and displacement
  // The displacement in metres from the three noises' values, at most `displacement` long.
  glm::dvec3 displacement(float x, float y, float z) const;
  glm::dvec3 noise_point(const glm::dvec3& q) const;  // n: stretched
  glm::dvec3 wrapped(const glm::dvec3& q) const;      // q moved into the periodic tile (x, y)
  void make_map();           // map_ from the parameters' image (or file) and extent
  void replicate_shapes();   // periodic: shapes moved into the tile, copies across its edges
  Aabb world_box(const Aabb& q0_box) const;
  Aabb lean(double z_lo, double z_hi) const;  // the shear's horizontal offsets over that height
  // s: the shapes' coverage at q, with the base and the ceiling at the undisplaced altitude z0.
  double coverage_at(const glm::dvec3& q, double z0) const;
  // coverage_at at every point not skipped (s = 0 there), the shapes' roughness noise evaluated
  // in one batch: the same values.
  void coverages(const std::vector<std::array<double, 3>>& q, const std::vector<double>& z0,
                 const std::vector<uint8_t>& skip, std::vector<double>& s) const;
  // densities() in stages, on per-thread working memory. far_points: which of the points q0
  // no displacement can move into a shape (all 0 without displacement).
  std::vector<uint8_t>& far_points(const std::vector<std::array<double, 3>>& q) const;
  // The billow, erosion, furrow and cauliflower noise of the points that densities() found
  // coverage enough for, and their densities into out.
  void finish_busy(const std::vector<double>& s, const std::vector<double>& z0, float* out) const;
  double calm(double z0) const;  // w: the noise's share near the base and the ceiling
  // The density function before erosion, furrows and cauliflower take their share: an upper
  // bound of finish's argument (they only take away), so where it is <= 0 the density is 0
  // whatever those noises give, and they need not be evaluated.
  double unbitten(double s, double w, float billow_noise) const;
  float finish(double s, double w, float billow_noise, float detail, float furrow, float cauli) const;

  CloudParams params_;
  std::vector<Shape> shapes_;
  std::vector<Shape> bound_shapes_;  // bound_shape of each: its distance bound's smooth shape
  std::unique_ptr<ShapeIndex> index_;
  double shear_base_ = 0.0;
  glm::dvec2 fibre_dir_{1.0, 0.0};
  std::unique_ptr<noise::PerlinWorleyField> cauli_;
  double time_;
  double threshold_;            // 1 - coverage
  double mean_;                 // mean(fbm): 0 but for Worley noise
  double inv_sd_;               // 1 / sd(fbm)
  double min_useful_coverage_;
  std::unique_ptr<noise::NoiseField> billow_, detail_, furrow_, disp_[3];
  std::optional<PeriodicTile> tile_;
  std::unique_ptr<CoverageMap> map_;
};

}  // namespace nimbus::volume
