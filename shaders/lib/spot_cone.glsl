// A spot's cone (light.hpp): the weight of its propagation direction, full within the inner
// cone, smoothstep to 0 at the outer one, w = smoothstep(cos outer, cos inner, cos angle); a
// hard cone (inner == outer) is 1 inside and 0 outside. Common subset of GLSL and C++
// (render::spot_weight is the same formula in double).
#ifndef NIMBUS_SPOT_CONE_GLSL
#define NIMBUS_SPOT_CONE_GLSL

float spot_cone_weight(float cos_angle, float cos_outer, float cos_inner) {
  if (!(cos_inner > cos_outer)) return cos_angle >= cos_inner ? 1.0f : 0.0f;
  float t = clamp((cos_angle - cos_outer) / (cos_inner - cos_outer), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

#endif
