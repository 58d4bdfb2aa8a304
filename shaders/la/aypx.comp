#version 450
#extension GL_GOOGLE_include_directive : require
// y = x + a y
#include "../common/sessile.glsl"
#include "../common/vecpush.glsl"
layout(std430, binding = 1) readonly buffer X { REAL4 x[]; };
layout(std430, binding = 2) buffer Y { REAL4 y[]; };
void main() {
  uint i = sessile_gid();
  if (i >= pc.n4 || guarded()) return;
  y[pc.off1 + i] = x[pc.off0 + i] + coef() * y[pc.off1 + i];
}
