#version 450
#extension GL_GOOGLE_include_directive : require
// y = A x (SELL-8, as spmv_csr.comp) fused with the partial sums of x·y
// (set 0): CG needs p·Ap right after Ap, and one pass saves re-reading both.
// Grid-stride over rows, at most MAXG groups; the stride is a multiple of 8
// (the group size is), so lane j keeps row j of every slice it visits.
#include "../common/sessile.glsl"
#include "../common/reduce_shared.glsl"
layout(push_constant) uniform SpmvPush {
  uint nrows;
  uint xoff, yoff;   // in reals
  int guard;
  uint rows_per;     // unused
} pc;
layout(std430, binding = 0) buffer Scalars { REAL s[]; };
layout(std430, binding = 1) readonly buffer RP { uint slice_ptr[]; };
layout(std430, binding = 2) readonly buffer C { uvec4 col[]; };
layout(std430, binding = 3) readonly buffer V { REAL4 val[]; };
layout(std430, binding = 4) readonly buffer X { REAL x[]; };
layout(std430, binding = 5) writeonly buffer Y { REAL y[]; };
layout(std430, binding = 6) writeonly buffer PART { REAL2 part[]; };
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  REAL2 acc = REAL2(0);
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint row = gl_GlobalInvocationID.x; row < pc.nrows; row += stride) {
    uint sl = row >> 3u;
    uint k = slice_ptr[sl] + (row & 7u), e = slice_ptr[sl + 1u];
    REAL sum = REAL(0);
    for (; k < e; k += 8u) {
      uvec4 c = col[k] + uvec4(pc.xoff);
      REAL4 v = val[k];
      sum += v.x * x[c.x] + v.y * x[c.y] + v.z * x[c.z] + v.w * x[c.w];
    }
    y[pc.yoff + row] = sum;
    acc_add(acc, sum * x[pc.xoff + row]);
  }
  REAL2 t = group_reduce(acc);
  if (gl_LocalInvocationID.x == 0u) part[gl_WorkGroupID.x] = t;
}
