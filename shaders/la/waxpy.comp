#version 450
#extension GL_GOOGLE_include_directive : require
// w = a x + y
#include "la_kernels.glsl"
#include "../common/vecpush.glsl"
void main() {
  uint i = sessile_gid();
  if (i >= pc.n4 || guarded()) return;
  w[pc.off2 + i] = coef() * x[pc.off0 + i] + y[pc.off1 + i];
}
