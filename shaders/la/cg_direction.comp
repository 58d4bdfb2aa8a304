#version 450
#extension GL_GOOGLE_include_directive : require
// CG search direction without storing z: p = D⁻¹ r + β p.
#include "../common/sessile.glsl"
#include "../common/vecpush.glsl"
#include "../common/solver_slots.glsl"
layout(std430, binding = 1) readonly buffer D { REAL4 dinv[]; };
layout(std430, binding = 2) readonly buffer R { REAL4 r[]; };
layout(std430, binding = 3) buffer P { REAL4 p[]; };
void main() {
  uint i = sessile_gid();
  if (i >= pc.n4 || guarded()) return;
  p[i] = dinv[i] * r[i] + s[CG_BETA] * p[i];
}
