#version 450 core
// The clouds' shadow map (clouds/cloud_shadow.hpp): one invocation per map texel marches that texel's
// light ray through one cloud, adding its optical depth and widening the depth range of its
// matter. Dispatched once per cloud; the texel's values accumulate across clouds.
layout(local_size_x = 8, local_size_y = 8) in;
#include "lib/cloud_block.glsl"
layout(r32f, binding = IMAGE_CLOUD_TAU) uniform image2D u_tau;
layout(rg32f, binding = IMAGE_CLOUD_RANGE) uniform image2D u_range;
#include "lib/cloud_density.glsl"  // the cloud (its CloudBlock: world_to_texture, sigma_t, blend)
uniform vec3 u_origin;             // world point of the map's corner (texel 0, 0) on its plane
uniform vec3 u_axis_x;             // map width vector, metres
uniform vec3 u_axis_y;             // map height vector, metres
uniform vec3 u_to_sun;             // unit, towards the sun (light propagates along -u_to_sun)
uniform float u_depth0;            // march from this depth (metres along the light from the plane)
uniform float u_step;              // metres
uniform int u_steps;
uniform int u_res;
uniform vec3 u_box_min;            // the cloud's support (world metres): no density outside it
uniform vec3 u_box_max;

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (px.x >= u_res || px.y >= u_res) return;
  vec2 st = (vec2(px) + 0.5) / float(u_res);
  vec3 p0 = u_origin + st.x * u_axis_x + st.y * u_axis_y;
  float tau = 0.0;
  float first = 3.0e38, last = -3.0e38;
  // Only the steps whose midpoints can lie inside the support box: the rest sample zero. Most
  // texels of the map miss a given cloud entirely and march nothing.
  vec3 dir = -u_to_sun;  // the light's propagation direction
  vec3 d = vec3(abs(dir.x) > 1.0e-9 ? dir.x : 1.0e-9, abs(dir.y) > 1.0e-9 ? dir.y : 1.0e-9,
                abs(dir.z) > 1.0e-9 ? dir.z : 1.0e-9);  // an axis-parallel sun: no 0 * inf
  vec3 inv = 1.0 / d;
  vec3 ta = (u_box_min - p0) * inv, tb = (u_box_max - p0) * inv;
  float t0 = max(max(min(ta.x, tb.x), min(ta.y, tb.y)), min(ta.z, tb.z));
  float t1 = min(min(max(ta.x, tb.x), max(ta.y, tb.y)), max(ta.z, tb.z));
  int k0 = clamp(int(floor((t0 - u_depth0) / u_step - 0.5)) - 1, 0, u_steps);
  int k1 = clamp(int(ceil((t1 - u_depth0) / u_step - 0.5)) + 1, 0, u_steps);
  if (!(t1 >= t0)) k1 = k0;
  for (int k = k0; k < k1; ++k) {
    float depth = u_depth0 + (float(k) + 0.5) * u_step;  // midpoint rule
    vec3 tc = (cloud.world_to_texture * vec4(p0 + depth * dir, 1.0)).xyz;
    float rho = cloud_density(tc);
    tau += cloud.sigma_t * rho * u_step;
    bool matter = rho > 0.0;
    first = matter ? min(first, depth - 0.5 * u_step) : first;
    last = matter ? max(last, depth + 0.5 * u_step) : last;
  }
  float old_tau = imageLoad(u_tau, px).r;
  vec2 old_range = imageLoad(u_range, px).rg;
  imageStore(u_tau, px, vec4(old_tau + tau, 0.0, 0.0, 0.0));
  imageStore(u_range, px, vec4(min(old_range.x, first), max(old_range.y, last), 0.0, 0.0));
}
