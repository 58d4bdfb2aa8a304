#version 450
#extension GL_GOOGLE_include_directive : require
// MG-PCG step fused with the V-cycle's first sweep: x += α p; r -= α q;
// z = w r with w = omega / (h diag) on free nodes and 1 on Dirichlet nodes
// (mg_smooth.glsl from x = 0; w is made at each solve's start by
// stencil7_cut_jacobi with h / omega); partial sums of r·r into set off2.
#include "la_kernels.glsl"
#include "../common/vecpush.glsl"
#include "../common/reduce_shared.glsl"
void main() {
  if (guarded()) return;
  REAL a = s[CG_ALPHA];
  REAL2 rr = REAL2(0);
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < pc.n4; i += stride) {
    x[i] += a * p[i];
    REAL4 ri = r[i] - a * q[i];
    r[i] = ri;
    z[i] = w[i] * ri;
    REAL4 u = ri * ri;
    acc_add(rr, u.x); acc_add(rr, u.y); acc_add(rr, u.z); acc_add(rr, u.w);
  }
  REAL2 t = group_reduce(rr);
  if (gl_LocalInvocationID.x == 0u) part[pc.off2 * MAXG + gl_WorkGroupID.x] = t;
}
