#version 450 core
// GL test pattern (tests/gl/test_gl_*.cpp): each pixel's window coordinates, a uniform passed
// through an included function, and the full-screen triangle's uv in a second target.
#include "test_lib.glsl"

in vec2 uv;
uniform float value;

layout(location = 0) out vec4 coords;
layout(location = 1) out vec4 texcoords;

void main() {
  coords = vec4(gl_FragCoord.xy, test_lib_scale(value), 1.0);
  texcoords = vec4(uv, 0.0, 1.0);
}
