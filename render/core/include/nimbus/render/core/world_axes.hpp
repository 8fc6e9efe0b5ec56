// Where nimbus's world meets its renderer's frame. nimbus's world is Z-up: x east, y north,
// z up, metres (Blender's convention). It holds for every flag, file, view state, script and the
// Python module. The renderer works in OpenGL's Y-up frame (x east, y up, -z north), and these
// two maps are the only place the two meet: a proper quarter turn about x, nothing mirrored
// (volume/up_axis.hpp turns grids the same way).
#pragma once
#include <glm/vec3.hpp>

namespace nimbus::render {

// World (x east, y north, z up) to the renderer's frame: (x, y, z) -> (x, z, -y).
constexpr glm::dvec3 world_to_render(const glm::dvec3& w) { return {w.x, w.z, -w.y}; }

// The renderer's frame back to the world: (x, y, z) -> (x, -z, y).
constexpr glm::dvec3 render_to_world(const glm::dvec3& r) { return {r.x, -r.z, r.y}; }

}  // namespace nimbus::render
