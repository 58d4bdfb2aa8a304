#version 450
#extension GL_GOOGLE_include_directive : require
// BiCGSTAB search direction: p = r + β (p − ω v); on a restart (the shadow
// residual lost to rounding, bicgstab_scalar op 1) r̂0 = r and p = r.
#include "la_kernels.glsl"
#include "../common/vecpush.glsl"
void main() {
  uint i = sessile_gid();
  if (i >= pc.n4 || guarded()) return;
  if (s[BI_RESTART] != REAL(0)) {
    r0[i] = r[i];
    p[i] = r[i];
  } else {
    p[i] = r[i] + s[BI_BETA] * (p[i] - s[BI_OMEGA] * v[i]);
  }
}
