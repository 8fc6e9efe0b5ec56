// Triangle meshes of the light-shaft scene for the GL renderer: the same surfaces the CPU
// reference intersects exactly (the ground plane as a large quad, spheres tessellated).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "nimbus/render/scene/scene.hpp"

namespace nimbus::render {

// One vertex: world position (metres), unit normal, and a colour: the Lambert albedo for scene
// surfaces, the emitted radiance (W sr^-1 m^-2) for light bulbs (build_bulb_mesh).
struct MeshVertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec3 albedo;
};

// Indexed triangles, counter-clockwise seen from the side the normal points to (GL's default
// front face).
struct SceneMesh {
  std::vector<MeshVertex> vertices;
  std::vector<std::uint32_t> indices;  // 3 per triangle
};

// Tessellation of spheres in build_scene_mesh: longitude x latitude segments. The mesh is
// inscribed in the sphere (vertices on it); its largest gap to the true surface, at the
// midpoints of the equatorial quads' diagonals, is r (1 - cos(sqrt(2) pi / kSphereSlices))
// ~= 2.4e-3 r (tested), so GL silhouettes and shadows are that much smaller than the reference's.
inline constexpr int kSphereSlices = 64;  // around the y axis
inline constexpr int kSphereStacks = 32;  // pole to pole

// All scene surfaces. The infinite ground plane becomes a quad of half-extent
// ground_extent_m (> 0, else std::invalid_argument) centred below the scene camera's eye;
// boxes are 12 triangles with flat normals; spheres kSphereSlices x kSphereStacks with exact
// (smooth) normals; the heightfield its exact triangles (diagonal from (ix, iz) to
// (ix+1, iz+1), as Heightfield and the reference intersect them) with flat normals.
SceneMesh build_scene_mesh(const Scene& scene, double ground_extent_m);

// The visible bulbs of the scene's point lights: a sphere of bulb_radius_m per light
// (kBulbSlices x kBulbStacks, inscribed), colour = radiance I0 / (pi r^2).
inline constexpr int kBulbSlices = 32;
inline constexpr int kBulbStacks = 16;
SceneMesh build_bulb_mesh(const Scene& scene);
SceneMesh build_bulb_mesh(const Light& light);

}  // namespace nimbus::render
