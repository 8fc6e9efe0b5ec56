#version 450 core
// GL test (tests/gl/test_gl_readback.cpp): every ShaderProgram::set overload's value, written out.
uniform int i1;
uniform float f1;
uniform vec2 f2;
uniform vec3 f3;
uniform vec4 f4;
uniform ivec2 i2;
uniform mat4 m4;
uniform uint u1;
uniform float unused_f;  // declared, never read: the compiler drops it

layout(location = 0) out vec4 out0;
layout(location = 1) out vec4 out1;
layout(location = 2) out vec4 out2;
layout(location = 3) out vec4 out3;

void main() {
  out0 = vec4(float(i1), f1, vec2(i2));
  out1 = f4;
  out2 = m4 * vec4(f3, f2.x) + vec4(0.0, 0.0, 0.0, f2.y);
  out3 = vec4(float(u1), 0.0, 0.0, 1.0);
}
