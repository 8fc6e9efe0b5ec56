// GL meshes of the scene: triangle counts, orientation, and agreement with the exact surfaces
// the reference intersects (tessellation error of spheres as documented).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "nimbus/render/scene/intersect.hpp"
#include "nimbus/render/scene/scene_mesh.hpp"

namespace nr = nimbus::render;

namespace {

glm::dvec3 pos(const nr::SceneMesh& m, std::size_t i) { return glm::dvec3(m.vertices[m.indices[i]].position); }

// Every triangle is counter-clockwise seen from the side its vertex normals face.
void expect_oriented(const nr::SceneMesh& m) {
  ASSERT_EQ(m.indices.size() % 3, 0u);
  for (std::size_t i = 0; i < m.indices.size(); i += 3) {
    const glm::dvec3 n = glm::cross(pos(m, i + 1) - pos(m, i), pos(m, i + 2) - pos(m, i));
    ASSERT_GT(glm::length(n), 0.0) << "degenerate triangle " << i / 3;
    for (int k = 0; k < 3; ++k) {
      ASSERT_GT(glm::dot(n, glm::dvec3(m.vertices[m.indices[i + k]].normal)), 0.0) << "triangle " << i / 3;
    }
  }
}

double total_area(const nr::SceneMesh& m) {
  double a = 0.0;
  for (std::size_t i = 0; i < m.indices.size(); i += 3) {
    a += 0.5 * glm::length(glm::cross(pos(m, i + 1) - pos(m, i), pos(m, i + 2) - pos(m, i)));
  }
  return a;
}

}  // namespace

TEST(SceneMesh, BoxesAndGroundQuad) {
  nr::Scene s;
  s.camera.eye = {5.0, 1.7, -3.0};
  s.ground = nr::GroundPlane{-0.5, {{0.2, 0.3, 0.4}}};
  s.boxes.push_back({{0, 0, 0}, {1, 2, 3}, {{0.5, 0.6, 0.7}}});
  const nr::SceneMesh m = nr::build_scene_mesh(s, 100.0);
  EXPECT_EQ(m.indices.size(), 3u * (2 + 12));
  expect_oriented(m);
  // Ground: 200 m square centred under the eye; box: its surface area 2 (2 + 3 + 6) = 22.
  EXPECT_NEAR(total_area(m), 200.0 * 200.0 + 22.0, 1e-6);
  double xmin = 1e9, xmax = -1e9;
  for (int i = 0; i < 4; ++i) {
    EXPECT_FLOAT_EQ(m.vertices[i].position.y, -0.5f);
    EXPECT_EQ(m.vertices[i].albedo, glm::vec3(0.2f, 0.3f, 0.4f));
    xmin = std::min(xmin, double(m.vertices[i].position.x));
    xmax = std::max(xmax, double(m.vertices[i].position.x));
  }
  EXPECT_FLOAT_EQ(xmin, -95.0f);
  EXPECT_FLOAT_EQ(xmax, 105.0f);
  // Flat, axis-aligned, outward box normals: each vertex lies on the face its normal names.
  for (std::size_t i = 4; i < m.vertices.size(); ++i) {
    const glm::dvec3 p(m.vertices[i].position), n(m.vertices[i].normal);
    const glm::dvec3 centre{0.5, 1.0, 1.5}, half{0.5, 1.0, 1.5};
    EXPECT_NEAR(glm::dot(p - centre, n), glm::dot(glm::abs(n), half), 1e-6);
  }
  EXPECT_THROW(nr::build_scene_mesh(s, 0.0), std::invalid_argument);
  EXPECT_THROW(nr::build_scene_mesh(s, std::nan("")), std::invalid_argument);
}

TEST(SceneMesh, SphereTessellationErrorIsAsDocumented) {
  nr::Scene s;
  const double r = 2.0;
  s.spheres.push_back({{1, 2, 3}, r, {{0.3, 0.3, 0.3}}});
  const nr::SceneMesh m = nr::build_scene_mesh(s, 10.0);
  expect_oriented(m);
  EXPECT_EQ(m.indices.size() / 3, static_cast<std::size_t>(2 * nr::kSphereSlices * (nr::kSphereStacks - 1)));
  // Vertices on the sphere; the largest gap inside a triangle (over a fine barycentric grid)
  // is about r (1 - cos(pi/64 * sqrt 2)) = 2.4e-3 r, at the equator's quad diagonals.
  double worst = 0.0;
  for (std::size_t i = 0; i < m.indices.size(); i += 3) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(glm::length(pos(m, i + k) - glm::dvec3{1, 2, 3}), r, 1e-5);
    for (int a = 0; a <= 8; ++a) {
      for (int b = 0; a + b <= 8; ++b) {
        const glm::dvec3 p = (double(a) * pos(m, i) + double(b) * pos(m, i + 1) + double(8 - a - b) * pos(m, i + 2)) / 8.0;
        worst = std::max(worst, r - glm::length(p - glm::dvec3{1, 2, 3}));
      }
    }
  }
  const double documented = r * (1.0 - std::cos(M_PI / nr::kSphereSlices * std::sqrt(2.0)));
  EXPECT_LE(worst, documented * 1.01);
  EXPECT_GE(worst, documented * 0.9);
  EXPECT_NEAR(total_area(m), 4.0 * M_PI * r * r, 4.0 * M_PI * r * r * 3e-3);
}

TEST(SceneMesh, TerrainTrianglesAreTheHeightfieldSurface) {
  nr::Scene s = nr::make_scene("terrain");
  s.ground.reset();  // the terrain's triangles alone
  const nr::SceneMesh m = nr::build_scene_mesh(s, 10.0);
  const nr::Heightfield& h = *s.terrain;
  EXPECT_EQ(m.indices.size() / 3, static_cast<std::size_t>(2 * (h.nx - 1) * (h.nz - 1)));
  expect_oriented(m);
  for (std::size_t i = 0; i < m.indices.size(); i += 3) {
    const glm::dvec3 c = (pos(m, i) + pos(m, i + 1) + pos(m, i + 2)) / 3.0;
    EXPECT_NEAR(c.y, *nr::heightfield_height(h, c.x, c.z), 1e-4) << i / 3;  // float vertices
  }
}

TEST(SceneMesh, BulbsCarryTheirRadiance) {
  const nr::Scene s = nr::make_scene("lamps");
  const nr::SceneMesh all = nr::build_bulb_mesh(s);
  const nr::SceneMesh one = nr::build_bulb_mesh(s.lamps[1]);
  expect_oriented(all);
  EXPECT_EQ(all.vertices.size(), 3 * one.vertices.size());
  const nr::Light& l = s.lamps[1];
  const glm::dvec3 radiance = l.intensity_w_sr / (M_PI * l.bulb_radius_m * l.bulb_radius_m);
  for (const nr::MeshVertex& v : one.vertices) {
    EXPECT_NEAR(glm::length(glm::dvec3(v.position) - l.position_m), l.bulb_radius_m, 1e-6);
    EXPECT_NEAR(v.albedo.x, radiance.x, radiance.x * 1e-6);
    EXPECT_NEAR(v.albedo.z, radiance.z, radiance.z * 1e-6);
  }
}

// A radius of 0 hides a bulb: no triangles, and the reference sees no bulb either.
TEST(SceneMesh, HiddenBulbsHaveNoGeometry) {
  nr::Scene s = nr::make_scene("lamps");
  for (nr::Light& l : s.lamps) l.bulb_radius_m = 0.0;
  nr::validate(s);
  EXPECT_TRUE(nr::build_bulb_mesh(s).indices.empty());
  EXPECT_TRUE(nr::build_bulb_mesh(s.lamps[0]).vertices.empty());
  const glm::dvec3 dir = glm::normalize(s.lamps[0].position_m - s.camera.eye);
  EXPECT_FALSE(nr::intersect_bulbs(s, s.camera.eye, dir, 1e9).has_value());
}

TEST(SceneMesh, EveryPresetBuilds) {
  for (const std::string& name : nr::scene_names()) {
    const nr::Scene s = nr::make_scene(name);
    const nr::SceneMesh m = nr::build_scene_mesh(s, 1000.0);
    EXPECT_EQ(m.indices.size() % 3, 0u) << name;
    for (const std::uint32_t i : m.indices) ASSERT_LT(i, m.vertices.size()) << name;
    if (name != "open") {
      EXPECT_FALSE(m.indices.empty()) << name;
    }
  }
}
