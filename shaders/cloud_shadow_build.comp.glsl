#version 450 core
// The clouds' shadow map (clouds/cloud_shadow.hpp): one invocation per map texel marches that texel's
// light ray through one cloud, adding its optical depth and widening the depth range of its
// matter. Dispatched once per cloud; the texel's values accumulate across clouds.
layout(local_size_x = 8, local_size_y = 8) in;
#include "lib/cloud_block.glsl"
layout(r32f, binding = IMAGE_CLOUD_TAU) uniform image2D u_tau;
layout(rg32f, binding = IMAGE_CLOUD_RANGE) uniform image2D u_range;
#include "lib/cloud_density.glsl"  // the cloud (its CloudBlock: world_to_texture, sigma_t, blend)
// One cloud's march (uniform_blocks.hpp's CloudShadowMarchBlock).
layout(std140, binding = BLOCK_CLOUD_SHADOW_MARCH) uniform CloudShadowMarchBlock {
  vec3 origin;   // world point of the map's corner (texel 0, 0) on its plane
  int res;       // texels per side
  vec3 axis_x;   // map width vector, metres
  int steps;
  vec3 axis_y;   // map height vector, metres
  float depth0;  // march from this depth (metres along the light from the plane)
  vec3 to_sun;   // unit, towards the sun (light propagates along -to_sun)
  float step_m;  // metres
  vec3 box_min;  // the cloud's support (world metres): no density outside it
  vec3 box_max;
} march;

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (px.x >= march.res || px.y >= march.res) return;
  vec2 st = (vec2(px) + 0.5) / float(march.res);
  vec3 p0 = march.origin + st.x * march.axis_x + st.y * march.axis_y;
  float tau = 0.0;
  float first = 3.0e38, last = -3.0e38;
  // Only the steps whose midpoints can lie inside the support box: the rest sample zero. Most
  // texels of the map miss a given cloud entirely and march nothing.
  vec3 dir = -march.to_sun;  // the light's propagation direction
  vec3 d = vec3(abs(dir.x) > 1.0e-9 ? dir.x : 1.0e-9, abs(dir.y) > 1.0e-9 ? dir.y : 1.0e-9,
                abs(dir.z) > 1.0e-9 ? dir.z : 1.0e-9);  // an axis-parallel sun: no 0 * inf
  vec3 inv = 1.0 / d;
  vec3 ta = (march.box_min - p0) * inv, tb = (march.box_max - p0) * inv;
  float t0 = max(max(min(ta.x, tb.x), min(ta.y, tb.y)), min(ta.z, tb.z));
  float t1 = min(min(max(ta.x, tb.x), max(ta.y, tb.y)), max(ta.z, tb.z));
  int k0 = clamp(int(floor((t0 - march.depth0) / march.step_m - 0.5)) - 1, 0, march.steps);
  int k1 = clamp(int(ceil((t1 - march.depth0) / march.step_m - 0.5)) + 1, 0, march.steps);
  if (!(t1 >= t0)) k1 = k0;
  for (int k = k0; k < k1; ++k) {
    float depth = march.depth0 + (float(k) + 0.5) * march.step_m;  // midpoint rule
    vec3 tc = (cloud.world_to_texture * vec4(p0 + depth * dir, 1.0)).xyz;
    float rho = cloud_density(tc);
    tau += cloud.sigma_t * rho * march.step_m;
    bool matter = rho > 0.0;
    first = matter ? min(first, depth - 0.5 * march.step_m) : first;
    last = matter ? max(last, depth + 0.5 * march.step_m) : last;
  }
  float old_tau = imageLoad(u_tau, px).r;
  vec2 old_range = imageLoad(u_range, px).rg;
  imageStore(u_tau, px, vec4(old_tau + tau, 0.0, 0.0, 0.0));
  imageStore(u_range, px, vec4(min(old_range.x, first), max(old_range.y, last), 0.0, 0.0));
}
