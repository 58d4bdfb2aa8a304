#version 450
#extension GL_GOOGLE_include_directive : require
// BiCGSTAB update: x += α p̂ + ω ŝ; r = s − ω t; partial sums of r·r (set 0)
// and r̂0·r (set 1).
#include "la_kernels.glsl"
#include "../common/vecpush.glsl"
#include "../common/reduce_shared.glsl"
void main() {
  if (guarded()) return;
  REAL a = s[BI_ALPHA], w = s[BI_OMEGA];
  REAL2 rr = REAL2(0), rho = REAL2(0);
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < pc.n4; i += stride) {
    x[i] += a * ph[i] + w * sh[i];
    REAL4 ri = sv[i] - w * t[i];
    r[i] = ri;
    REAL4 u = ri * ri, v = r0[i] * ri;
    acc_add(rr, u.x); acc_add(rr, u.y); acc_add(rr, u.z); acc_add(rr, u.w);
    acc_add(rho, v.x); acc_add(rho, v.y); acc_add(rho, v.z); acc_add(rho, v.w);
  }
  REAL2 a0 = group_reduce(rr);
  REAL2 a1 = group_reduce(rho);
  if (gl_LocalInvocationID.x == 0u) {
    part[gl_WorkGroupID.x] = a0;
    part[MAXG + gl_WorkGroupID.x] = a1;
  }
}
