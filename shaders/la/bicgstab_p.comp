#version 450
#extension GL_GOOGLE_include_directive : require
// BiCGSTAB search direction: p = r + β (p − ω v).
#include "../common/sessile.glsl"
#include "../common/vecpush.glsl"
#include "../common/solver_slots.glsl"
layout(std430, binding = 1) readonly buffer R { REAL4 r[]; };
layout(std430, binding = 2) readonly buffer V { REAL4 v[]; };
layout(std430, binding = 3) buffer P { REAL4 p[]; };
void main() {
  uint i = sessile_gid();
  if (i >= pc.n4 || guarded()) return;
  p[i] = r[i] + s[BI_BETA] * (p[i] - s[BI_OMEGA] * v[i]);
}
