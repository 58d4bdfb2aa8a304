#version 450
#extension GL_GOOGLE_include_directive : require
// BiCGSTAB search direction: p = r + β (p − ω v).
#include "la_kernels.glsl"
#include "../common/vecpush.glsl"
void main() {
  uint i = sessile_gid();
  if (i >= pc.n4 || guarded()) return;
  p[i] = r[i] + s[BI_BETA] * (p[i] - s[BI_OMEGA] * v[i]);
}
