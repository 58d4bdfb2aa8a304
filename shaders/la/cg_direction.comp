#version 450
#extension GL_GOOGLE_include_directive : require
// CG search direction without storing z: p = D⁻¹ r + β p.
#include "la_kernels.glsl"
#include "../common/vecpush.glsl"
void main() {
  uint i = sessile_gid();
  if (i >= pc.n4 || guarded()) return;
  p[i] = dinv[i] * r[i] + s[CG_BETA] * p[i];
}
