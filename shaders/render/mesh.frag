#version 450
#extension GL_GOOGLE_include_directive : require
// Lambert shading with a key and a fill light and an ambient term
// (docs/render.md, "Lights"): c = colour * (ambient + sum w max(0, n.l)),
// clamped to 1.  Two-sided: a normal facing away from the camera is
// flipped, so open and inconsistently wound meshes shade as seen.  The
// colour attachment is UNORM: this value is the 8-bit value / 255.
#include "mesh_push.glsl"
layout(location = 0) in vec3 v_pos;
layout(location = 1) in vec3 v_normal;
layout(location = 2) in vec4 v_color;
layout(location = 0) out vec4 out_color;
void main() {
  if (pc.params.y == 0.0) {
    out_color = vec4(v_color.rgb, 1.0);
    return;
  }
  vec3 n = v_normal;
  float len = length(n);
  n = len > 0.0 ? n / len : vec3(0.0, 0.0, 1.0);
  vec3 v = pc.eye.w > 0.0 ? normalize(pc.eye.xyz - v_pos) : pc.eye.xyz;
  if (dot(n, v) < 0.0) n = -n;
  float shade = pc.params.x + pc.key.w * max(dot(n, pc.key.xyz), 0.0) +
                pc.fill.w * max(dot(n, pc.fill.xyz), 0.0);
  out_color = vec4(min(v_color.rgb * shade, vec3(1.0)), 1.0);
}
