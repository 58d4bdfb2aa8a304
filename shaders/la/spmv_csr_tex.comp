#version 450
#extension GL_GOOGLE_include_directive : require
// y = A x, CSR as sliced ELL (SELL-8) read from uniform texel buffers:
// see spmv_sell.glsl.  One row per invocation.
#define SELL_TEXEL 1
#include "spmv_sell.glsl"
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint row = sessile_gid();
  if (row >= pc.nrows) return;
  y[pc.yoff + row] = sell_row(row);
}
