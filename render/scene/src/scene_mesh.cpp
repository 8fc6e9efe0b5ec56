// Triangle meshes of the light-shaft scene (ground quad, boxes, tessellated spheres, terrain
// triangles, light bulbs) for the GL renderer.
#include "nimbus/render/scene/scene_mesh.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace nimbus::render {
namespace {

std::uint32_t push_vertex(SceneMesh& m, const glm::dvec3& p, const glm::dvec3& n, const glm::dvec3& c) {
  m.vertices.push_back({glm::vec3(p), glm::vec3(n), glm::vec3(c)});
  return static_cast<std::uint32_t>(m.vertices.size() - 1);
}

// Appends a triangle, ordered counter-clockwise as seen from the side its vertex normals face.
void push_triangle(SceneMesh& m, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  const glm::dvec3 pa(m.vertices[a].position), pb(m.vertices[b].position), pc(m.vertices[c].position);
  const glm::dvec3 n = glm::dvec3(m.vertices[a].normal) + glm::dvec3(m.vertices[b].normal) +
                       glm::dvec3(m.vertices[c].normal);
  if (glm::dot(glm::cross(pb - pa, pc - pa), n) < 0.0) std::swap(b, c);
  m.indices.insert(m.indices.end(), {a, b, c});
}

void add_quad(SceneMesh& m, const glm::dvec3 (&p)[4], const glm::dvec3& n, const glm::dvec3& c) {
  std::uint32_t v[4];
  for (int i = 0; i < 4; ++i) v[i] = push_vertex(m, p[i], n, c);
  push_triangle(m, v[0], v[1], v[2]);
  push_triangle(m, v[0], v[2], v[3]);
}

void add_box(SceneMesh& m, const Box& b) {
  const glm::dvec3 lo = b.min_m, hi = b.max_m;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      glm::dvec3 n{0.0};
      n[axis] = side ? 1.0 : -1.0;
      glm::dvec3 p[4];
      const double uv[4][2] = {{lo[u], lo[v]}, {hi[u], lo[v]}, {hi[u], hi[v]}, {lo[u], hi[v]}};
      for (int k = 0; k < 4; ++k) {
        p[k][axis] = side ? hi[axis] : lo[axis];
        p[k][u] = uv[k][0];
        p[k][v] = uv[k][1];
      }
      add_quad(m, p, n, b.material.albedo);
    }
  }
}

// Latitude-longitude sphere with vertices on the true surface (an inscribed polyhedron).
void add_sphere(SceneMesh& m, const glm::dvec3& centre, double radius, const glm::dvec3& colour,
                int slices, int stacks) {
  const std::uint32_t base = static_cast<std::uint32_t>(m.vertices.size());
  for (int i = 0; i <= stacks; ++i) {
    const double theta = M_PI * i / stacks;
    for (int j = 0; j <= slices; ++j) {
      const double phi = 2.0 * M_PI * j / slices;
      // Exact poles (sin(pi) is not 0 in double) so the pole triangles close.
      const double st = (i == 0 || i == stacks) ? 0.0 : std::sin(theta);
      const double ct = i == 0 ? 1.0 : (i == stacks ? -1.0 : std::cos(theta));
      const glm::dvec3 n{st * std::cos(phi), ct, st * std::sin(phi)};
      push_vertex(m, centre + radius * n, n, colour);
    }
  }
  auto at = [&](int i, int j) { return base + static_cast<std::uint32_t>(i * (slices + 1) + j); };
  for (int i = 0; i < stacks; ++i) {
    for (int j = 0; j < slices; ++j) {
      if (i != 0) push_triangle(m, at(i, j), at(i + 1, j), at(i, j + 1));
      if (i != stacks - 1) push_triangle(m, at(i, j + 1), at(i + 1, j), at(i + 1, j + 1));
    }
  }
}

void add_heightfield(SceneMesh& m, const Heightfield& h) {
  auto vertex = [&](int ix, int iz) {
    return glm::dvec3{h.x0_m + ix * h.spacing_m, h.heights_m[static_cast<std::size_t>(iz) * h.nx + ix],
                      h.z0_m + iz * h.spacing_m};
  };
  for (int iz = 0; iz + 1 < h.nz; ++iz) {
    for (int ix = 0; ix + 1 < h.nx; ++ix) {
      const glm::dvec3 p00 = vertex(ix, iz), p10 = vertex(ix + 1, iz);
      const glm::dvec3 p01 = vertex(ix, iz + 1), p11 = vertex(ix + 1, iz + 1);
      // Same split as intersect.cpp: diagonal p00-p11, counter-clockwise seen from above.
      const glm::dvec3 tris[2][3] = {{p00, p11, p10}, {p00, p01, p11}};
      for (const auto& t : tris) {
        const glm::dvec3 n = glm::normalize(glm::cross(t[1] - t[0], t[2] - t[0]));
        const std::uint32_t a = push_vertex(m, t[0], n, h.material.albedo);
        const std::uint32_t b = push_vertex(m, t[1], n, h.material.albedo);
        const std::uint32_t c = push_vertex(m, t[2], n, h.material.albedo);
        m.indices.insert(m.indices.end(), {a, b, c});
      }
    }
  }
}

}  // namespace

SceneMesh build_scene_mesh(const Scene& scene, double ground_extent_m) {
  if (!std::isfinite(ground_extent_m) || !(ground_extent_m > 0.0)) {
    throw std::invalid_argument("ground_extent_m: must be finite and > 0, got " +
                                std::to_string(ground_extent_m));
  }
  SceneMesh m;
  if (scene.ground) {
    const double e = ground_extent_m, y = scene.ground->height_m;
    const double cx = scene.camera.eye.x, cz = scene.camera.eye.z;
    const glm::dvec3 p[4] = {{cx - e, y, cz - e}, {cx + e, y, cz - e}, {cx + e, y, cz + e}, {cx - e, y, cz + e}};
    add_quad(m, p, {0.0, 1.0, 0.0}, scene.ground->material.albedo);
  }
  for (const Box& b : scene.boxes) add_box(m, b);
  for (const Sphere& s : scene.spheres) {
    add_sphere(m, s.centre_m, s.radius_m, s.material.albedo, kSphereSlices, kSphereStacks);
  }
  if (scene.terrain) add_heightfield(m, *scene.terrain);
  return m;
}

SceneMesh build_bulb_mesh(const Light& light) {
  SceneMesh m;
  const double r = light.bulb_radius_m;
  if (!(r > 0.0)) return m;  // no visible bulb
  add_sphere(m, light.position_m, r, light.intensity_w_sr / (M_PI * r * r), kBulbSlices, kBulbStacks);
  return m;
}

SceneMesh build_bulb_mesh(const Scene& scene) {
  SceneMesh m;
  for (const Light& l : scene.lamps) {
    const double r = l.bulb_radius_m;
    if (!(r > 0.0)) continue;  // no visible bulb
    add_sphere(m, l.position_m, r, l.intensity_w_sr / (M_PI * r * r), kBulbSlices, kBulbStacks);
  }
  return m;
}

}  // namespace nimbus::render
