#version 450
#extension GL_GOOGLE_include_directive : require
// Partial sums of x·y: each group writes one compensated (hi, lo) pair into
// partial set `off2`; reduce.comp finishes the sum in a fixed order, so the
// result is deterministic.  Grid-stride over at most MAXG groups.
#include "la_kernels.glsl"
#include "../common/vecpush.glsl"
#include "../common/reduce_shared.glsl"
void main() {
  if (guarded()) return;
  REAL2 acc = REAL2(0);
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < pc.n4; i += stride) {
    REAL4 p = x[pc.off0 + i] * y[pc.off1 + i];
    acc_add(acc, p.x);
    acc_add(acc, p.y);
    acc_add(acc, p.z);
    acc_add(acc, p.w);
  }
  REAL2 t = group_reduce(acc);
  if (gl_LocalInvocationID.x == 0u) part[pc.off2 * MAXG + gl_WorkGroupID.x] = t;
}
