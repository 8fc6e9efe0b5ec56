#version 450 core
// One triangle covering the viewport, from gl_VertexID alone (draw 3 vertices with an empty
// vertex array). uv runs over [0, 1] across the viewport, (0, 0) at the bottom-left (GL window origin).
out vec2 uv;

void main() {
  // Vertices (0,0), (2,0), (0,2) in uv: the viewport's unit square lies inside the triangle.
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  uv = p;
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
