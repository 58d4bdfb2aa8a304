#version 450
#extension GL_GOOGLE_include_directive : require
// BiCGSTAB half step: s = r − α v, with partial sums of s·s (set 0).
#include "la_kernels.glsl"
#include "../common/vecpush.glsl"
#include "../common/reduce_shared.glsl"
void main() {
  if (guarded()) return;
  REAL a = s[BI_ALPHA];
  REAL2 ss = REAL2(0);
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < pc.n4; i += stride) {
    REAL4 si = r[i] - a * v[i];
    sv[i] = si;
    REAL4 t = si * si;
    acc_add(ss, t.x); acc_add(ss, t.y); acc_add(ss, t.z); acc_add(ss, t.w);
  }
  REAL2 a0 = group_reduce(ss);
  if (gl_LocalInvocationID.x == 0u) part[gl_WorkGroupID.x] = a0;
}
