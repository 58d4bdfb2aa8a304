#version 450
#extension GL_GOOGLE_include_directive : require
// y = x
#include "la_kernels.glsl"
#include "../common/vecpush.glsl"
void main() {
  uint i = sessile_gid();
  if (i >= pc.n4 || guarded()) return;
  y[pc.off1 + i] = x[pc.off0 + i];
}
