// The size factor (cloud_scale.hpp).
#include "nimbus/volume/cloud_scale.hpp"

#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

namespace nimbus::volume {
namespace {

// Below this an altitude means "none" (base_altitude -1e30: no base; ceiling 1e30: no ceiling).
constexpr double kNoAltitude = 1e29;

bool set_altitude(double z) { return std::abs(z) < kNoAltitude; }

}  // namespace

void check_size_factor(double factor, const char* name) {
  if (factor >= kMinSizeFactor && factor <= kMaxSizeFactor) return;
  std::ostringstream text;
  text << name << ": must be within [" << kMinSizeFactor << ", " << kMaxSizeFactor << "], got " << factor;
  throw std::invalid_argument(text.str());
}

glm::dvec3 base_centre(const CloudParams& p) {
  std::optional<glm::dvec3> lowest;
  for (const Shape& s : p.shapes) {
    double bottom = s.center.z - s.size.z;
    if (s.kind == ShapeKind::Capsule) bottom = std::min(s.center.z, s.end.z) - s.size.x;
    if (!lowest || bottom < lowest->z) lowest = glm::dvec3(s.center.x, s.center.y, bottom);
  }
  glm::dvec3 c = lowest.value_or(glm::dvec3(0.0));
  if (p.field) c = glm::dvec3(p.field->center_m, c.z);
  if (set_altitude(p.base_altitude)) c.z = p.base_altitude;
  return c;
}

CloudParams scale_cloud(const CloudParams& p, double f) {
  check_size_factor(f, "size");
  if (f == 1.0) return p;
  const glm::dvec3 base = base_centre(p);
  const auto about = [&](glm::dvec3 x) { return base + f * (x - base); };
  const auto altitude = [&](double z) { return set_altitude(z) ? base.z + f * (z - base.z) : z; };
  CloudParams q = p;
  for (Shape& s : q.shapes) {
    s.center = about(s.center);
    if (s.kind == ShapeKind::Capsule) s.end = about(s.end);
    s.size *= f;
  }
  if (q.field) {
    q.field->center_m = glm::dvec2(base) + f * (q.field->center_m - glm::dvec2(base));
    q.field->size_m *= f;
    q.field->min_diameter_m *= f;
    q.field->max_diameter_m *= f;
  }
  q.base_softness *= f;
  q.ceiling_softness *= f;
  q.flat_layer *= f;
  q.displacement *= f;
  q.temperature_height *= f;
  q.ceiling_altitude = altitude(q.ceiling_altitude);
  q.stretch_altitude = altitude(q.stretch_altitude);
  q.temperature_base = altitude(q.temperature_base);
  q.period_m *= f;
  // The coverage map's extent (west, south, east, north) about the base centre; all 0 stays "auto".
  if (p.coverage_map_extent != std::array<double, 4>{0.0, 0.0, 0.0, 0.0})
    for (int i = 0; i < 4; ++i) {
      const double centre = i % 2 == 0 ? base.x : base.y;  // west, south, east, north
      q.coverage_map_extent[i] = centre + f * (p.coverage_map_extent[i] - centre);
    }
  for (double* frequency : {&q.frequency, &q.erosion_frequency, &q.furrow_frequency, &q.displacement_frequency,
                            &q.cauliflower_frequency})
    *frequency /= f;
  return q;
}

}  // namespace nimbus::volume
