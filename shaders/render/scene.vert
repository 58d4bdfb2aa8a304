#version 450
#extension GL_GOOGLE_include_directive : require
// Instanced scene vertices (docs/render.md, "Scenes"): per vertex the
// position (mesh units) and normal, per instance the transform to world cm
// (four columns) and the instance's base colour.  Normals go through the
// inverse transpose, so a non-uniform scale shades right; mesh.frag lights
// the result exactly as a single mesh.
#include "mesh_push.glsl"
layout(location = 0) in vec3 in_pos;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec4 in_m0;
layout(location = 3) in vec4 in_m1;
layout(location = 4) in vec4 in_m2;
layout(location = 5) in vec4 in_m3;
layout(location = 6) in vec4 in_color;
layout(location = 0) out vec3 v_pos;
layout(location = 1) out vec3 v_normal;
layout(location = 2) out vec4 v_color;
void main() {
  mat4 model = mat4(in_m0, in_m1, in_m2, in_m3);
  vec4 w = model * vec4(in_pos, 1.0);
  v_pos = w.xyz;
  v_normal = transpose(inverse(mat3(model))) * in_normal;
  v_color = in_color;
  gl_Position = pc.mvp * w;
}
