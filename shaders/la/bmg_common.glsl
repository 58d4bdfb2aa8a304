// Shared by the block multigrid kernels (bmg_*.comp).
#ifndef BMG_COMMON_GLSL
#define BMG_COMMON_GLSL
// The free unknowns of a node's mask as 0/1 factors.
REAL4 bmg_free(uint m) {
  return REAL4((m & 1u) != 0u ? 1 : 0, (m & 2u) != 0u ? 1 : 0, (m & 4u) != 0u ? 1 : 0,
               (m & 8u) != 0u ? 1 : 0);
}
#ifdef BMG_ROWS
// b - A x for block row `row` of the bound chunk (node = row0 + row).
REAL4 bmg_row_residual(uint row, REAL4 bv) {
  REAL4 r = bv;
  uint e = rowptr[row + 1u];
  for (uint k = rowptr[row]; k < e; k++) {
    REAL4 xb = x[col[k]];
    uint v = 4u * k;
    r -= REAL4(dot(val[v], xb), dot(val[v + 1u], xb), dot(val[v + 2u], xb), dot(val[v + 3u], xb));
  }
  return r;
}
#endif
#endif
