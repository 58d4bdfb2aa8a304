#version 450
#extension GL_GOOGLE_include_directive : require
// CG step, fused: x += α p; r -= α q; partial sums of r·D⁻¹r (set 0) and r·r
// (set 1).  z = D⁻¹ r is never stored: cg_direction.comp recomputes it.
#include "la_kernels.glsl"
#include "../common/vecpush.glsl"
#include "../common/reduce_shared.glsl"
void main() {
  if (guarded()) return;
  REAL a = s[CG_ALPHA];
  REAL2 rz = REAL2(0), rr = REAL2(0);
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < pc.n4; i += stride) {
    x[i] += a * p[i];
    REAL4 ri = r[i] - a * q[i];
    r[i] = ri;
    REAL4 zi = dinv[i] * ri;
    REAL4 t = ri * zi, u = ri * ri;
    acc_add(rz, t.x); acc_add(rz, t.y); acc_add(rz, t.z); acc_add(rz, t.w);
    acc_add(rr, u.x); acc_add(rr, u.y); acc_add(rr, u.z); acc_add(rr, u.w);
  }
  REAL2 a0 = group_reduce(rz);
  REAL2 a1 = group_reduce(rr);
  if (gl_LocalInvocationID.x == 0u) {
    part[gl_WorkGroupID.x] = a0;
    part[MAXG + gl_WorkGroupID.x] = a1;
  }
}
