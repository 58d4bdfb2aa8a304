#version 450
#extension GL_GOOGLE_include_directive : require
// Finishes reductions: workgroup k sums the `count` partial pairs of set
// first_set + k in a fixed order and stores s[dst_slot + k] (its square root
// when sqrt_flag is set).
#include "la_kernels.glsl"
#include "../common/reduce_shared.glsl"
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint set = pc.first_set + gl_WorkGroupID.x;
  REAL2 acc = REAL2(0);
  for (uint i = gl_LocalInvocationID.x; i < pc.count; i += gl_WorkGroupSize.x)
    acc_merge(acc, part[set * MAXG + i]);
  REAL2 t = group_reduce(acc);
  if (gl_LocalInvocationID.x == 0u) {
    REAL v = acc_value(t);
    // A sum of squares is >= 0; no clamp, so a NaN stays a NaN (max(NaN, 0) is 0).
    s[pc.dst_slot + int(gl_WorkGroupID.x)] = pc.sqrt_flag != 0u ? sqrt(v) : v;
  }
}
