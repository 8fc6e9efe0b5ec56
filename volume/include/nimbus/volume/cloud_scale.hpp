// The size factor: a cloud's parameters made f times as large about its base centre, so that one
// preset gives the same cloud at another size (`nimbus generate --size`, Python's size=, the
// Blender add-on's Size factor).
#pragma once
#include <glm/vec3.hpp>

#include "nimbus/volume/cloud_model.hpp"

namespace nimbus::volume {

// The size factors nimbus takes, [kMinSizeFactor, kMaxSizeFactor].
inline constexpr double kMinSizeFactor = 0.01;
inline constexpr double kMaxSizeFactor = 100.0;

// Throws std::invalid_argument "`name`: must be within [0.01, 100], got X" for a factor outside
// the range (NaN included).
void check_size_factor(double factor, const char* name);

// Where a cloud stands, metres: below the centre of its lowest shape (a field's: the field's
// centre), at base_altitude where it is set, else at that shape's bottom (0 without shapes).
glm::dvec3 base_centre(const CloudParams& p);

// `p` made `factor` times as large about base_centre(p):
//   lengths times f: shapes' centres, capsule ends and sizes; the field's centre, area and
//     diameters; base and ceiling softness, flat layer, displacement, temperature height; the
//     periodic tile; the coverage map's extent;
//   altitudes about the base: ceiling, fibres (stretch), temperature base;
//   noise frequencies divided by f, so the billows grow with the cloud.
// A field's clouds keep their species' depth rule (cloud_field.hpp: a mediocris stays under 1 km
// deep), so a field grows across and its clouds' depths follow their new diameters.
// Unchanged: what has no length (coverage, billow, erosion, shear in m/m, roughness, densities)
// and the wind, the evolution and the seed: a cloud twice the size drifts at the same speed.
// factor 1 returns `p` as it is. Throws as check_size_factor("size").
CloudParams scale_cloud(const CloudParams& p, double factor);

}  // namespace nimbus::volume
