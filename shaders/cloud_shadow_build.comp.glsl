#version 450 core
// The clouds' shadow map (clouds/cloud_shadow.hpp): one invocation per map texel marches that texel's
// light ray through one cloud, adding its optical depth and widening the depth range of its
// matter. Dispatched once per cloud; the texel's values accumulate across clouds.
layout(local_size_x = 8, local_size_y = 8) in;
#include "lib/cloud_block.glsl"
layout(r32f, binding = IMAGE_CLOUD_TAU) uniform image2D u_tau;
layout(rg32f, binding = IMAGE_CLOUD_RANGE) uniform image2D u_range;
layout(binding = UNIT_CLOUD_DENSITY) uniform sampler3D u_density;  // the cloud (its CloudBlock: world_to_texture, sigma_t), border 0
uniform vec3 u_origin;             // world point of the map's corner (texel 0, 0) on its plane
uniform vec3 u_axis_x;             // map width vector, metres
uniform vec3 u_axis_y;             // map height vector, metres
uniform vec3 u_dir;                // light propagation direction (unit)
uniform float u_depth0;            // march from this depth (metres along u_dir from the plane)
uniform float u_step;              // metres
uniform int u_steps;
uniform int u_res;

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (px.x >= u_res || px.y >= u_res) return;
  vec2 st = (vec2(px) + 0.5) / float(u_res);
  vec3 p0 = u_origin + st.x * u_axis_x + st.y * u_axis_y;
  float tau = 0.0;
  float first = 3.0e38, last = -3.0e38;
  for (int k = 0; k < u_steps; ++k) {
    float depth = u_depth0 + (float(k) + 0.5) * u_step;  // midpoint rule
    vec3 tc = (cloud.world_to_texture * vec4(p0 + depth * u_dir, 1.0)).xyz;
    float rho = textureLod(u_density, tc, 0.0).r;
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
