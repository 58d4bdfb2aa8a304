/* The welded surface's last pass (docs/weld.md): drop the components that
 * are not the coral's outside.  Where three or more branches fuse they can
 * enclose a pocket of water: marching tetrahedra draws its wall as a closed
 * component facing inward (negative enclosed volume), faces buried inside
 * the solid that a renderer or a printer should not see.  A component that
 * encloses less than one grid cell is a sampling speck (a lone node inside
 * the level set), not a branch: dropped too.  Order is kept, so the GPU path
 * and the reference, which share this pass, still give the same bytes. */
#include <stdlib.h>
#include <string.h>
#include "weld_internal.h"

static uint32_t root(uint32_t *u, uint32_t x) {
  while (u[x] != x) x = u[x] = u[u[x]];
  return x;
}

sessile_status weld_drop_pockets(double *pos, uint32_t *nv, uint32_t *tri, uint32_t *nf, uint32_t *nearest,
                                 double min_volume) {
  uint32_t n = *nv, m = *nf;
  if (!n || !m) return SESSILE_OK;
  uint32_t *u = malloc((size_t)n * sizeof *u);
  double *vol = calloc((size_t)n, sizeof *vol);
  if (!u || !vol) {
    free(u), free(vol);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "welded surface: out of host memory for %u vertices", n);
  }
  for (uint32_t v = 0; v < n; v++) u[v] = v;
  for (uint32_t f = 0; f < m; f++) {
    uint32_t a = root(u, tri[3 * (size_t)f]), b = root(u, tri[3 * (size_t)f + 1]), c = root(u, tri[3 * (size_t)f + 2]);
    if (a != b) u[a > b ? a : b] = a < b ? a : b;
    a = root(u, a), c = root(u, c);
    if (a != c) u[a > c ? a : c] = a < c ? a : c;
  }
  /* enclosed volume per component (divergence theorem, about the first
   * vertex so that coordinates far from the origin lose no digits) */
  const double *o = pos;
  for (uint32_t f = 0; f < m; f++) {
    const double *p[3];
    for (int k = 0; k < 3; k++) p[k] = pos + 3 * (size_t)tri[3 * (size_t)f + k];
    double a[3], b[3], c[3];
    for (int k = 0; k < 3; k++) a[k] = p[0][k] - o[k], b[k] = p[1][k] - o[k], c[k] = p[2][k] - o[k];
    vol[root(u, tri[3 * (size_t)f])] += (a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
                                         a[2] * (b[0] * c[1] - b[1] * c[0])) / 6;
  }
  /* flatten (ascending: a root's index is the smallest of its component,
   * so every u[x], x < v, is final when v is reached), then compact in
   * order: vertex v keeps its rank among the kept ones, u[v] its new index */
  for (uint32_t v = 0; v < n; v++) u[v] = u[u[v]];
  uint32_t k = 0;
  for (uint32_t v = 0; v < n; v++) {
    uint32_t r = u[v]; /* r <= v: u[r] already rewritten when r < v */
    int keep = vol[r] >= min_volume;
    if (keep) {
      memmove(pos + 3 * (size_t)k, pos + 3 * (size_t)v, 3 * sizeof *pos);
      nearest[k] = nearest[v];
    }
    u[v] = keep ? k++ : UINT32_MAX;
  }
  /* a dropped triangle's corners are all dropped */
  uint32_t g = 0;
  for (uint32_t f = 0; f < m; f++) {
    uint32_t a = u[tri[3 * (size_t)f]];
    if (a == UINT32_MAX) continue;
    tri[3 * (size_t)g] = a, tri[3 * (size_t)g + 1] = u[tri[3 * (size_t)f + 1]], tri[3 * (size_t)g + 2] = u[tri[3 * (size_t)f + 2]];
    g++;
  }
  *nv = k, *nf = g;
  free(u), free(vol);
  return SESSILE_OK;
}
