#version 450
#extension GL_GOOGLE_include_directive : require
// One level of a block ILU(0) triangular solve, 4x4 block CSR (host/la/ilu.c):
// one block row per invocation; blocks are four REAL4 rows, x and y REAL4 per node.
//   diag = 0 (L, unit lower):  y_i = x_i − Σ_j L_ij y_j
//   diag = 1 (U):              y_i = U_ii⁻¹ (x_i − Σ_j U_ij y_j), the dense
//                              inverse pivot block stored as the row's first entry
// For U, x and y are the same vector (in place).
#include "la_kernels.glsl"
REAL4 bmul(uint k, REAL4 v) {
  uint b = 4u * k;
  return REAL4(dot(val[b], v), dot(val[b + 1u], v), dot(val[b + 2u], v), dot(val[b + 3u], v));
}
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint t = sessile_gid();
  if (t >= pc.count) return;
  uint p = pc.first + t;
  uint i = order[p];
  uint k = rowptr[p], e = rowptr[p + 1u];
  uint dk = k;
  if (pc.diag != 0u) k++;
  REAL4 sum = x[pc.xoff + i];
  for (; k < e; k++) sum -= bmul(k, y[pc.yoff + col[k]]);
  if (pc.diag != 0u) sum = bmul(dk, sum);
  y[pc.yoff + i] = sum;
}
