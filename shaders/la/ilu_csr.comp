#version 450
#extension GL_GOOGLE_include_directive : require
// One level of an ILU(0) triangular solve, scalar CSR (host/la/ilu.c):
// every row of the level at once, one row per invocation.
//   diag = 0 (L, unit lower):  y_i = x_i − Σ_j L_ij y_j
//   diag = 1 (U):              y_i = (1/u_ii) (x_i − Σ_j U_ij y_j), the
//                              inverse pivot stored as the row's first entry
// The rows read y_j of earlier levels only (written by earlier dispatches);
// for U, x and y are the same vector (in place).
#include "la_kernels.glsl"
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
