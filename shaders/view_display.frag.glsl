#version 450 core
// The viewer's display pass: the finished frame (premultiplied radiance, row 0 at the top, any
// size: linear filtering scales it to the window) exposed, tone mapped (AgX) and sRGB-encoded as
// the PNG screenshots are, plus a triangular dither of one 8-bit code, which hides the banding of
// smooth sky gradients in 8 bits (sebh/UnrealEngineSkyAtmosphere#15).
#include "lib/contract.glsl"
#include "lib/tonemap.glsl"
in vec2 uv;
layout(binding = UNIT_SCENE_COLOR) uniform sampler2D u_frame;
uniform float u_exposure;   // 2^stops
uniform float u_dither;     // 1: dither; 0: exact codes (tests)
layout(location = 0) out vec4 o_color;

float hash(vec2 p) {  // a white-noise value in [0, 1) per pixel
  return fract(sin(dot(p, vec2(12.9898, 78.233))) * 43758.5453);
}

void main() {
  vec3 c = texture(u_frame, vec2(uv.x, 1.0 - uv.y)).rgb * u_exposure;
  vec3 e = srgb_encode(agx(c));
  float n = hash(gl_FragCoord.xy) + hash(gl_FragCoord.xy + 17.0) - 1.0;  // triangular in (-1, 1)
  o_color = vec4(e + u_dither * n / 255.0, 1.0);
}
