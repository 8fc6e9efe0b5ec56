// A field of many clouds over an area of kilometres (sizes as observed: Stull 2017, DeWitt et al. 2024): cloud
// diameters drawn from a power law, placed until the shapes cover a fraction of the area, each
// with its own species, seed and depth, all on the field's common flat base (the lifting
// condensation level). The clouds are shapes for one CloudModel, so a field is a pure function of
// world position: any sub-box generated alone matches the whole.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "nimbus/volume/shape.hpp"

namespace nimbus::volume {

// Cloud species a field can hold; each is a template of shapes scaled by the cloud's diameter.
enum class Species {
  Humilis,    // depth about the diameter up to 350 m (the inversion): large ones are flat; one dome
  Mediocris,  // depth about the diameter up to 1 km; a body and three rising turrets
  Congestus,  // depth about 1.5 diameters up to 3.5 km; a tower of five turrets
};

struct SpeciesShare {
  Species species = Species::Humilis;
  double share = 1.0;  // relative weight, >= 0
};

struct CloudFieldParams {
  glm::dvec2 center_m{0.0, 0.0};        // centre of the area (x east, y north)
  glm::dvec2 size_m{10000.0, 10000.0};  // extent of the area where cloud centres fall
  // Fraction of the area under the clouds' shapes, (0, 0.9]. The outlines that an observer
  // measures (optical depth >= 1) cover less: the billows and the gas function eat the edges.
  double coverage = 0.38;
  // Footprint area distribution dn/dlog a ~ a^-size_exponent between the diameters below
  // (a = footprint area). The outlines an observer measures come out flatter: edges eaten
  // below optical depth 1 shrink small clouds more, and rough edges shed fragments. 1.15 makes
  // the measured outlines' exponent about the observed 0.87 (DeWitt et al. 2024; docs/volume.md
  // has the measurement). [0, 3]
  double size_exponent = 1.15;
  double min_diameter_m = 100.0;
  double max_diameter_m = 2500.0;
  std::vector<SpeciesShare> species{{Species::Humilis, 0.6}, {Species::Mediocris, 0.4}};
  double depth_scale = 1.0;             // multiplies every cloud's depth (cloud_field.cpp), (0, 4]
  // Fractal outlines (Shape::roughness) of every cloud's shapes, [0, 1]: 0.6 gives outlines of
  // perimeter-area dimension about 1.29 (observed 1.33-1.38; docs/volume.md).
  double roughness = 0.6;
  uint32_t seed = 0;                    // the layout: positions, sizes, species, per-cloud seeds
  // A sky without edges: the field repeats with period size_m in x and y. The layout wraps (the
  // no-overlap test uses wrapped distances, and the model replicates the shapes that cross an
  // edge), and the cloud model makes every noise periodic with the same period (cloud_model.hpp).
  bool periodic = false;
};

// One placed cloud (what the layout drew).
struct FieldCloud {
  glm::dvec2 center_m{0.0};
  double diameter_m = 0.0;
  double depth_m = 0.0;
  Species species = Species::Humilis;
  uint32_t seed = 0;
  double roughness = 0.6;  // as CloudFieldParams::roughness
};

// Throws std::invalid_argument naming the parameter (prefixed by `where`).
void validate(const CloudFieldParams& p, const std::string& where = "field");

// The layout: diameters drawn until their footprints' summed area reaches coverage * area;
// then, largest first, each cloud's centre is drawn until its footprint overlaps no placed one
// (32 tries; a cloud that finds no room is dropped), so clouds touch at their rough edges but
// seldom merge into larger ones, which would flatten the size distribution. A pure function of the parameters. Refuses layouts of more than
// kMaxFieldClouds clouds by name (a minimum diameter far too small for the area).
inline constexpr size_t kMaxFieldClouds = 200000;
// With a coverage map (coverage_map.hpp), the covered area is coverage * the map's mean over the
// field times the area, each candidate centre is kept with probability map(centre) (a draw of
// its own stream, so a map of 1 everywhere gives the layout without a map), and, when the map
// also sets heights, a cloud's depth is multiplied by map(centre).
class CoverageMap;
std::vector<FieldCloud> field_layout(const CloudFieldParams& p, const CoverageMap* map = nullptr);

// The shapes of every cloud, their bases at base_altitude_m.
std::vector<Shape> field_shapes(const CloudFieldParams& p, double base_altitude_m, const CoverageMap* map = nullptr);
std::vector<Shape> cloud_shapes(const FieldCloud& c, double base_altitude_m);

const char* to_string(Species s);
bool parse_species(const std::string& text, Species* out);

}  // namespace nimbus::volume
