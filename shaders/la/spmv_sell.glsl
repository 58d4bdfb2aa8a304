// Row product of the CSR SpMV kernels, stored as sliced ELL (SELL-8) and
// included by spmv_csr*.comp with SELL_TEXEL set to 0 or 1.
//
// Slices of 8 consecutive rows; a slice stores its rows' entries in chunks of
// 4 (uvec4 columns, REAL4 values), row j's chunk t at slice_ptr[s] + 8 t + j,
// so the 8 lanes of a subgroup read one contiguous run per load (on lavapipe
// one sequential stream instead of 8-16 interleaved ones: 14 -> 9 ms for the
// P1-tet 64^3 matrix).  Rows shorter than their slice's widest are padded
// with value 0 and the row's last column (an Inf in x then cannot make NaN in
// a row that does not reference it).
//   SELL_TEXEL = 0: columns, values and x from storage buffers.
//   SELL_TEXEL = 1: from uniform texel buffers (texelFetch): lavapipe
//     gathers texels with vector loads where it scalarises storage-buffer
//     loads per lane, ~2.5x faster (docs/performance.md).  Texels are raw
//     bits: RGBA32UI for columns and values (a dvec4 is two texels), RG32UI
//     (fp64) or R32UI (fp32) for x.
#include "la_kernels.glsl"
#if SELL_TEXEL
uvec4 ld_col(uint k) { return texelFetch(col_t, int(k)); }
#if SESSILE_F64
REAL ld_x(uint i) { return packDouble2x32(texelFetch(x_t, int(i)).xy); }
REAL4 ld_val(uint k) {
  uvec4 a = texelFetch(val_t, int(2u * k)), b = texelFetch(val_t, int(2u * k + 1u));
  return REAL4(packDouble2x32(a.xy), packDouble2x32(a.zw), packDouble2x32(b.xy),
               packDouble2x32(b.zw));
}
#else
REAL ld_x(uint i) { return uintBitsToFloat(texelFetch(x_t, int(i)).x); }
REAL4 ld_val(uint k) { return uintBitsToFloat(texelFetch(val_t, int(k))); }
#endif
#else
uvec4 ld_col(uint k) { return col[k]; }
REAL4 ld_val(uint k) { return val[k]; }
REAL ld_x(uint i) { return x[i]; }
#endif

REAL sell_row(uint row) {
  uint sl = row >> 3u;
  uint k = slice_ptr[sl] + (row & 7u), e = slice_ptr[sl + 1u];
  REAL sum = REAL(0);
  for (; k < e; k += 8u) {
    uvec4 c = ld_col(k) + uvec4(pc.xoff);
    REAL4 v = ld_val(k);
    sum += v.x * ld_x(c.x) + v.y * ld_x(c.y) + v.z * ld_x(c.z) + v.w * ld_x(c.w);
  }
  return sum;
}
