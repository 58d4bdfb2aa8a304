#version 450
#extension GL_GOOGLE_include_directive : require
// w = x .* y (Jacobi application)
#include "../common/sessile.glsl"
#include "../common/vecpush.glsl"
layout(std430, binding = 1) readonly buffer X { REAL4 x[]; };
layout(std430, binding = 2) readonly buffer Y { REAL4 y[]; };
layout(std430, binding = 3) writeonly buffer W { REAL4 w[]; };
void main() {
  uint i = sessile_gid();
  if (i >= pc.n4 || guarded()) return;
  w[pc.off2 + i] = x[pc.off0 + i] * y[pc.off1 + i];
}
