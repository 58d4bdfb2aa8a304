#version 450
#extension GL_GOOGLE_include_directive : require
// y = a x + y
#include "la_kernels.glsl"
#include "../common/vecpush.glsl"
void main() {
  uint i = sessile_gid();
  if (i >= pc.n4 || guarded()) return;
  y[pc.off1 + i] += coef() * x[pc.off0 + i];
}
