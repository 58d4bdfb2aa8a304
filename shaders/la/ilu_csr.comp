#version 450
#extension GL_GOOGLE_include_directive : require
// One level of an ILU(0) triangular solve, scalar CSR (host/la/ilu.c):
// every row of the level at once, one row per invocation.
//   diag = 0 (L, unit lower):  y_i = x_i − Σ_j L_ij y_j
//   diag = 1 (U):              y_i = (1/u_ii) (x_i − Σ_j U_ij y_j), the
//                              inverse pivot stored as the row's first entry
// The rows read y_j of earlier levels only (written by earlier dispatches);
// for U, x and y are the same vector (in place).
#include "../common/sessile.glsl"
layout(push_constant) uniform IluPush {
  uint first, count;  // the level's positions [first, first + count)
  uint xoff, yoff;    // in REAL
  int guard;
  uint diag;
} pc;
layout(std430, binding = 0) buffer Scalars { REAL s[]; };
layout(std430, binding = 1) readonly buffer O { uint order[]; };
layout(std430, binding = 2) readonly buffer RP { uint rowptr[]; };
layout(std430, binding = 3) readonly buffer C { uint col[]; };
layout(std430, binding = 4) readonly buffer V { REAL val[]; };
layout(std430, binding = 5) readonly buffer X { REAL x[]; };
layout(std430, binding = 6) buffer Y { REAL y[]; };
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint t = sessile_gid();
  if (t >= pc.count) return;
  uint p = pc.first + t;
  uint i = order[p];
  uint k = rowptr[p], e = rowptr[p + 1u];
  REAL d = REAL(1);
  if (pc.diag != 0u) d = val[k++];
  REAL sum = x[pc.xoff + i];
  for (; k < e; k++) sum -= val[k] * y[pc.yoff + col[k]];
  y[pc.yoff + i] = d * sum;
}
