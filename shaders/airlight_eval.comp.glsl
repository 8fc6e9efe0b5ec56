#version 450 core
// Evaluates one airlight method per query with the shaders' own GLSL functions, for
// `nimbus airlight --device gl` and the tests (render/shafts/src/airlight_gl.cpp): queries in, La out.
#include "lib/airlight.glsl"
#include "lib/airlight_table.glsl"

layout(local_size_x = 64) in;

struct Query {
  float beta, I0, Dsv, Dvp, cos_gamma, sin_gamma;
  float march_length;  // raymarch: Dvp, or the cut-off of an infinite ray (computed on the CPU)
  float unused;
};
layout(std430, binding = STORAGE_AIRLIGHT_QUERIES) readonly buffer Queries { Query queries[]; };
layout(std430, binding = STORAGE_AIRLIGHT_RESULTS) writeonly buffer Results { float results[]; };

layout(binding = UNIT_F_TABLE) uniform sampler2D u_F_table;
uniform int u_method;  // AIRLIGHT_EVAL_* code
uniform int u_n;       // table size or steps
uniform int u_count;
uniform int u_offset;
uniform int u_phase_kind;  // PHASE_* code (stable and raymarch)
uniform float u_phase_g;

// N midpoint samples of Sun eq. 5 (thesis eq. 33 with a phase function) over [0, len] in float
// (the thesis' Algorithm 1 without occlusion).
float airlight_raymarch(float beta, float I0, float Dsv, float cos_gamma, float len, int steps) {
  if (!(beta > 0.0) || !(len > 0.0)) return 0.0;
  float dx = len / float(steps);
  float sum = 0.0;
  for (int k = 0; k < steps; ++k) {
    float x = (float(k) + 0.5) * dx;
    float d2 = Dsv * Dsv + x * x - 2.0 * x * Dsv * cos_gamma;
    float d = sqrt(d2);
    float p = phase_value(u_phase_kind, u_phase_g, (Dsv * cos_gamma - x) / d);
    sum += p * exp(-beta * (x + d)) / d2;
  }
  return beta * I0 * sum * dx;
}

void main() {
  int i = int(gl_GlobalInvocationID.x) + u_offset;
  if (i >= u_count) return;
  Query q = queries[i];
  float La;
  if (u_method == AIRLIGHT_EVAL_TABLE)
    La = airlight_table(u_F_table, u_n, q.beta, q.I0, q.Dsv, q.Dvp, q.cos_gamma, q.sin_gamma);
  else if (u_method == AIRLIGHT_EVAL_RAYMARCH)
    La = airlight_raymarch(q.beta, q.I0, q.Dsv, q.cos_gamma, q.march_length, u_n);
  else
    La = point_segment_airlight(q.beta, q.beta, q.I0, q.Dsv, q.cos_gamma, q.sin_gamma, 0.0, q.Dvp, u_phase_kind,
                                u_phase_g);
  results[i] = La;
}
