// The body of bmg_residual.comp and bmg_residual_tex.comp (BMG_TEXEL 0 or 1).
#include "la_kernels.glsl"
#define BMG_ROWS
#include "bmg_common.glsl"
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint g = sessile_gid();
  if (g >= pc.nrows) return;
  uint node = pc.row0 + g;
#if BMG_TEXEL
  y[node] = bmg_row_residual(g, bmg_tex4(b_t, node));
#else
  y[node] = bmg_row_residual(g, b[node]);
#endif
}
