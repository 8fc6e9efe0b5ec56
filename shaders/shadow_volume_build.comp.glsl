#version 450 core
// Shadow volume from a shadow map (after McCool 2000, thesis 4.3.1): wherever two neighbouring
// texels store distances that differ by more than a texel's worth, the boundary between lit
// and shadowed space runs between them; emit that "skirt" quad, spanning the two distances
// along the rays through the texels' shared edge. Continuous texels lie on occluder surfaces,
// which a view ray only reaches at its own end point, so they need no geometry.
// Point lights: one invocation per texel of each cube face (z = face); the neighbour is found by
// direction, so skirts also cross face seams. Sun: one invocation per texel of the 2D map.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
#include "lib/shadow_map_block.glsl"  // the map's light and the skirts' limits
layout(binding = UNIT_POINT_SHADOW) uniform samplerCubeArray u_cube;
layout(binding = UNIT_SUN_SHADOW) uniform sampler2D u_map;
layout(std430, binding = STORAGE_SKIRT_QUADS) buffer Quads { vec4 verts[]; };
layout(std430, binding = STORAGE_SKIRT_COUNTER) buffer Counter { uint quad_count; uint overflow; };

// GL 4.5 spec table 8.19: direction of cube face f at face coordinates sc, tc in [-1, 1].
vec3 cube_dir(int f, float sc, float tc) {
  if (f == 0) return vec3(1.0, -tc, -sc);
  if (f == 1) return vec3(-1.0, -tc, sc);
  if (f == 2) return vec3(sc, 1.0, tc);
  if (f == 3) return vec3(sc, -1.0, -tc);
  if (f == 4) return vec3(sc, -tc, 1.0);
  return vec3(-sc, -tc, -1.0);
}

// Direction at texel-grid coordinates (s, t) in [0, res] of face f.
vec3 grid_dir(int f, float s, float t) {
  return normalize(cube_dir(f, 2.0 * s / float(shadow_map.res) - 1.0, 2.0 * t / float(shadow_map.res) - 1.0));
}

float cube_distance(vec3 d) { return textureLod(u_cube, vec4(d, float(shadow_map.layer)), 0.0).r; }

// Each skirt is widened by kOverlap texels at both ends of its edge, so that skirts meeting at
// a T-junction (neighbours with different distance ranges) overlap instead of leaving cracks.
const float kOverlap = 0.05;

void emit(vec3 a, vec3 b, vec3 c, vec3 d) {
  uint q = atomicAdd(quad_count, 1u);
  if (q >= shadow_map.max_quads) { overflow = 1u; return; }
  uint v = q * 6u;
  verts[v + 0u] = vec4(a, 1.0); verts[v + 1u] = vec4(b, 1.0); verts[v + 2u] = vec4(c, 1.0);
  verts[v + 3u] = vec4(a, 1.0); verts[v + 4u] = vec4(c, 1.0); verts[v + 5u] = vec4(d, 1.0);
}

bool jump(float a, float b) { return abs(a - b) > shadow_map.rel_threshold * min(a, b); }

// Skirt of a point light along the grid edge (s0, t0)-(s1, t1) of face f, between distances a, b.
void cube_skirt(int f, vec2 p0, vec2 p1, float a, float b) {
  if (!jump(a, b)) return;
  vec2 along = (p1 - p0) * kOverlap;
  vec3 e1 = grid_dir(f, p0.x - along.x, p0.y - along.y);
  vec3 e2 = grid_dir(f, p1.x + along.x, p1.y + along.y);
  float n = min(min(a, b), shadow_map.max_distance), x = min(max(a, b), shadow_map.max_distance);
  if (x <= n) return;
  emit(shadow_map.origin + e1 * n, shadow_map.origin + e2 * n, shadow_map.origin + e2 * x, shadow_map.origin + e1 * x);
}

// Skirt of the sun along the map edge (s0, t0)-(s1, t1) (texel units), between distances a, b.
void sun_skirt(vec2 p0, vec2 p1, float a, float b) {
  if (!jump(a, b)) return;
  vec2 along = (p1 - p0) * kOverlap;
  float r = float(shadow_map.res);
  vec3 e1 = shadow_map.origin + shadow_map.axis_x * ((p0.x - along.x) / r) + shadow_map.axis_y * ((p0.y - along.y) / r);
  vec3 e2 = shadow_map.origin + shadow_map.axis_x * ((p1.x + along.x) / r) + shadow_map.axis_y * ((p1.y + along.y) / r);
  float n = min(min(a, b), shadow_map.max_distance), x = min(max(a, b), shadow_map.max_distance);
  if (x <= n) return;
  vec3 l = -shadow_map.to_sun;  // the sun's propagation direction
  emit(e1 + l * n, e2 + l * n, e2 + l * x, e1 + l * x);
}

void main() {
  ivec3 id = ivec3(gl_GlobalInvocationID);
  if (id.x >= shadow_map.res || id.y >= shadow_map.res) return;
  float i = float(id.x), j = float(id.y);
  if (shadow_map.mode == SHADOW_POINT_LIGHT) {
    int f = id.z;
    float dA = cube_distance(grid_dir(f, i + 0.5, j + 0.5));
    // +s and +t neighbours (found by direction, so across seams too).
    cube_skirt(f, vec2(i + 1.0, j), vec2(i + 1.0, j + 1.0), dA, cube_distance(grid_dir(f, i + 1.5, j + 0.5)));
    cube_skirt(f, vec2(i, j + 1.0), vec2(i + 1.0, j + 1.0), dA, cube_distance(grid_dir(f, i + 0.5, j + 1.5)));
    // Seams on the -s and -t borders: the adjacent face may not own them (its orientation
    // differs), so border texels emit them too; a seam emitted twice costs only fill.
    if (id.x == 0) cube_skirt(f, vec2(0.0, j), vec2(0.0, j + 1.0), dA, cube_distance(grid_dir(f, -0.5, j + 0.5)));
    if (id.y == 0) cube_skirt(f, vec2(i, 0.0), vec2(i + 1.0, 0.0), dA, cube_distance(grid_dir(f, i + 0.5, -0.5)));
  } else {
    float dA = texelFetch(u_map, id.xy, 0).r;
    if (id.x + 1 < shadow_map.res) sun_skirt(vec2(i + 1.0, j), vec2(i + 1.0, j + 1.0), dA, texelFetch(u_map, id.xy + ivec2(1, 0), 0).r);
    if (id.y + 1 < shadow_map.res) sun_skirt(vec2(i, j + 1.0), vec2(i + 1.0, j + 1.0), dA, texelFetch(u_map, id.xy + ivec2(0, 1), 0).r);
  }
}
