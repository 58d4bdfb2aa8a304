#version 450
#extension GL_GOOGLE_include_directive : require
// y = A x, CSR with every row padded to a multiple of 4 entries (padding:
// column 0, value 0) so columns and values load as uvec4 / REAL4: lavapipe
// scalarises per-lane loads, and wide loads cut their count by 4.
// `rows_per` consecutive rows per invocation.
#include "../common/sessile.glsl"
layout(push_constant) uniform SpmvPush {
  uint nrows;
  uint xoff, yoff;   // in reals
  int guard;
  uint rows_per;
} pc;
layout(std430, binding = 0) buffer Scalars { REAL s[]; };
layout(std430, binding = 1) readonly buffer RP { uint rowptr[]; };  // in chunks of 4
layout(std430, binding = 2) readonly buffer C { uvec4 col[]; };
layout(std430, binding = 3) readonly buffer V { REAL4 val[]; };
layout(std430, binding = 4) readonly buffer X { REAL x[]; };
layout(std430, binding = 5) writeonly buffer Y { REAL y[]; };
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint r0 = sessile_gid() * pc.rows_per;
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
  }
}
