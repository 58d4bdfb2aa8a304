// Shared by the block multigrid kernels (bmg_*.comp).
#ifndef BMG_COMMON_GLSL
#define BMG_COMMON_GLSL
// The free unknowns of a node's mask as 0/1 factors.
REAL4 bmg_free(uint m) {
  return REAL4((m & 1u) != 0u ? 1 : 0, (m & 2u) != 0u ? 1 : 0, (m & 4u) != 0u ? 1 : 0,
               (m & 8u) != 0u ? 1 : 0);
}
// The _tex kernels (BMG_TEXEL 1) read through uniform texel buffers of raw
// bits where their storage twins (BMG_TEXEL 0) read storage buffers:
// lavapipe gathers texels with vector loads where it loads storage lane by
// lane; the same values, so the same bits.  A REAL4 is two RGBA32UI texels
// in fp64, one in fp32.
#if BMG_TEXEL
#if SESSILE_F64
REAL4 bmg_tex4(usamplerBuffer t, uint i) {
  uvec4 a = texelFetch(t, int(2u * i)), c = texelFetch(t, int(2u * i + 1u));
  return REAL4(packDouble2x32(a.xy), packDouble2x32(a.zw), packDouble2x32(c.xy), packDouble2x32(c.zw));
}
#else
REAL4 bmg_tex4(usamplerBuffer t, uint i) { return uintBitsToFloat(texelFetch(t, int(i))); }
#endif
#endif
#ifdef BMG_ROWS
// The matrix rows and x.
#if BMG_TEXEL
uint bmg_rowptr(uint i) { return texelFetch(rowptr_t, int(i)).x; }
uint bmg_col(uint k) { return texelFetch(col_t, int(k)).x; }
REAL4 bmg_val(uint v) { return bmg_tex4(val_t, v); }
#if defined(BMG_X_STORAGE)
REAL4 bmg_x(uint i) { return x[i]; } // written in the same dispatch (bmg_smooth_wg)
#else
REAL4 bmg_x(uint i) { return bmg_tex4(x_t, i); }
#endif
#else
uint bmg_rowptr(uint i) { return rowptr[i]; }
uint bmg_col(uint k) { return col[k]; }
REAL4 bmg_val(uint v) { return val[v]; }
REAL4 bmg_x(uint i) { return x[i]; }
#endif
// b - A x for block row `row` of the bound chunk (node = row0 + row).
REAL4 bmg_row_residual(uint row, REAL4 bv) {
  REAL4 r = bv;
  uint e = bmg_rowptr(row + 1u);
  for (uint k = bmg_rowptr(row); k < e; k++) {
    REAL4 xb = bmg_x(bmg_col(k));
    uint v = 4u * k;
    r -= REAL4(dot(bmg_val(v), xb), dot(bmg_val(v + 1u), xb), dot(bmg_val(v + 2u), xb), dot(bmg_val(v + 3u), xb));
  }
  return r;
}
#endif
#endif
