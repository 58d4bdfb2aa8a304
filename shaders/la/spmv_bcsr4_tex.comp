#version 450
#extension GL_GOOGLE_include_directive : require
// spmv_bcsr4.comp reading rowptr, col, val and x through uniform texel
// buffers (bmg_common.glsl's raw-bit fetches: lavapipe gathers texels with
// vector loads where it loads storage lane by lane).  The same arithmetic in
// the same order, so the same bits.
#include "la_kernels.glsl"
#define BMG_TEXEL 1
#define BMG_ROWS
#include "bmg_common.glsl"
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint br = sessile_gid();
  if (br >= pc.nrows) return;
  REAL4 sum = REAL4(0);
  uint e = bmg_rowptr(br + 1u);
  for (uint k = bmg_rowptr(br); k < e; k++) {
    REAL4 xb = bmg_tex4(x_t, pc.xoff + bmg_col(k));
    uint v = 4u * k;
    sum += REAL4(dot(bmg_val(v), xb), dot(bmg_val(v + 1u), xb), dot(bmg_val(v + 2u), xb), dot(bmg_val(v + 3u), xb));
  }
  y[pc.yoff + br] = sum;
}
