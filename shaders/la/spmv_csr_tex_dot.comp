#version 450
#extension GL_GOOGLE_include_directive : require
// y = A x (SELL-8 from uniform texel buffers, spmv_sell.glsl) fused with the
// partial sums of x·y (set 0): CG needs p·Ap right after Ap, and one pass
// saves re-reading both.  Grid-stride over rows, at most MAXG groups; the
// stride is a multiple of 8 (the group size is), so lane j keeps row j of
// every slice it visits.
#define SELL_TEXEL 1
#include "spmv_sell.glsl"
#include "../common/reduce_shared.glsl"
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  REAL2 acc = REAL2(0);
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint row = gl_GlobalInvocationID.x; row < pc.nrows; row += stride) {
    REAL sum = sell_row(row);
    y[pc.yoff + row] = sum;
    acc_add(acc, sum * ld_x(pc.xoff + row));
  }
  REAL2 t = group_reduce(acc);
  if (gl_LocalInvocationID.x == 0u) part[gl_WorkGroupID.x] = t;
}
