#version 450
#extension GL_GOOGLE_include_directive : require
// Mesh and grid vertices: world position (cm), normal, colour.
#include "mesh_push.glsl"
layout(location = 0) in vec3 in_pos;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec4 in_color;
layout(location = 0) out vec3 v_pos;
layout(location = 1) out vec3 v_normal;
layout(location = 2) out vec4 v_color;
void main() {
  v_pos = in_pos;
  v_normal = in_normal;
  v_color = in_color;
  gl_Position = pc.mvp * vec4(in_pos, 1.0);
}
