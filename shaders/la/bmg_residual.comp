#version 450
#extension GL_GOOGLE_include_directive : require
// y = b - A x on one matrix row chunk (nodes row0 .. row0 + nrows - 1).
#include "la_kernels.glsl"
#define BMG_ROWS
#include "bmg_common.glsl"
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint g = sessile_gid();
  if (g >= pc.nrows) return;
  uint node = pc.row0 + g;
  y[node] = bmg_row_residual(g, b[node]);
}
