#version 450
#extension GL_GOOGLE_include_directive : require
// y = A x for 4x4 block CSR: one block row per invocation; x and y blocks are
// REAL4 (4 unknowns per node), each block four REAL4 rows.
#include "la_kernels.glsl"
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint br = sessile_gid();
  if (br >= pc.nrows) return;
  REAL4 sum = REAL4(0);
  uint e = rowptr[br + 1u];
  for (uint k = rowptr[br]; k < e; k++) {
    REAL4 xb = x[pc.xoff + col[k]];
    uint v = 4u * k;
    sum += REAL4(dot(val[v], xb), dot(val[v + 1u], xb), dot(val[v + 2u], xb), dot(val[v + 3u], xb));
  }
  y[pc.yoff + br] = sum;
}
