#version 450
#extension GL_GOOGLE_include_directive : require
// y = A x (padded CSR, as spmv_csr.comp) fused with the partial sums of x·y
// (set 0): CG needs p·Ap right after Ap, and one pass saves re-reading both.
// Grid-stride over blocks of rows_per rows, at most MAXG groups.
#include "../common/sessile.glsl"
#include "../common/reduce_shared.glsl"
layout(push_constant) uniform SpmvPush {
  uint nrows;
  uint xoff, yoff;   // in reals
  int guard;
  uint rows_per;
} pc;
layout(std430, binding = 0) buffer Scalars { REAL s[]; };
layout(std430, binding = 1) readonly buffer RP { uint rowptr[]; };
layout(std430, binding = 2) readonly buffer C { uvec4 col[]; };
layout(std430, binding = 3) readonly buffer V { REAL4 val[]; };
layout(std430, binding = 4) readonly buffer X { REAL x[]; };
layout(std430, binding = 5) writeonly buffer Y { REAL y[]; };
layout(std430, binding = 6) writeonly buffer PART { REAL2 part[]; };
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  REAL2 acc = REAL2(0);
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x * pc.rows_per;
  for (uint r0 = gl_GlobalInvocationID.x * pc.rows_per; r0 < pc.nrows; r0 += stride) {
    uint r1 = min(r0 + pc.rows_per, pc.nrows);
    for (uint row = r0; row < r1; row++) {
      REAL sum = REAL(0);
      uint e = rowptr[row + 1u];
      for (uint k = rowptr[row]; k < e; k++) {
        uvec4 c = col[k] + uvec4(pc.xoff);
        REAL4 v = val[k];
        sum += v.x * x[c.x] + v.y * x[c.y] + v.z * x[c.z] + v.w * x[c.w];
      }
      y[pc.yoff + row] = sum;
      acc_add(acc, sum * x[pc.xoff + row]);
    }
  }
  REAL2 t = group_reduce(acc);
  if (gl_LocalInvocationID.x == 0u) part[gl_WorkGroupID.x] = t;
}
