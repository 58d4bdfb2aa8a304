/* Colouring for the parallel Navier-Stokes assembly (ns_assemble.c).
 *
 * The unit coloured is a chunk of NS_CHUNK consecutive tets, not a tet: a
 * thread adds a whole chunk's element matrices in tet order, so the block
 * rows it touches stay in cache (a mesh in box or TetGen order is spatially
 * coherent).  Colouring single tets made each colour's pass touch every
 * block of the matrix, one cache miss per add: two thirds of the assembly's
 * time (perf, level 1, 2026-11-29; docs/fluid.md).  A mesh that is not a
 * box (TetGen's order is not spatial) is first put in Morton order. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fem/ns_internal.h"
#include "sessile/mesh/mesh_sort.h"

/* Greedy colouring of the chunks of `chunk` tets: no two chunks of a colour
 * share a node, so a colour's chunks scatter into disjoint block rows
 * without locks, and the sums' order (colour, chunk, tet) does not depend
 * on the thread count.  Returns the colours, 0 when more than 256 are
 * needed, -1 out of memory. */
static int colour_chunks(sessile_fluid *fl, uint32_t chunk) {
  enum { W = 4 }; /* up to 256 colours */
  uint32_t nch = (uint32_t)(((uint64_t)fl->ntets + chunk - 1) / chunk);
  uint64_t *used = calloc((size_t)fl->nnodes * W + 1, sizeof *used);
  uint32_t *col = malloc(((size_t)nch + 1) * sizeof *col);
  free(fl->cstart), free(fl->corder);
  fl->cstart = calloc(257, sizeof *fl->cstart);
  fl->corder = malloc(((size_t)nch + 1) * sizeof *fl->corder);
  int nc = used && col && fl->cstart && fl->corder ? 0 : -1;
  for (uint32_t ch = 0; nc >= 0 && ch < nch; ch++) {
    uint64_t t0 = (uint64_t)ch * chunk, t1 = t0 + chunk < fl->ntets ? t0 + chunk : fl->ntets;
    int c = -1;
    for (int wd = 0; wd < W && c < 0; wd++) {
      uint64_t m = 0;
      for (size_t k = 4 * (size_t)t0; k < 4 * (size_t)t1; k++) m |= used[(size_t)fl->tet[k] * W + wd];
      if (~m) c = 64 * wd + __builtin_ctzll(~m);
    }
    if (c < 0) {
      nc = 0;
      break;
    }
    for (size_t k = 4 * (size_t)t0; k < 4 * (size_t)t1; k++)
      used[(size_t)fl->tet[k] * W + c / 64] |= 1ull << (c % 64);
    col[ch] = (uint32_t)c;
    if (c + 1 > nc) nc = c + 1;
    fl->cstart[c + 1]++;
  }
  if (nc > 0) {
    for (int c = 0; c < nc; c++) fl->cstart[c + 1] += fl->cstart[c];
    uint32_t fillc[256];
    memcpy(fillc, fl->cstart, sizeof fillc);
    for (uint32_t ch = 0; ch < nch; ch++) fl->corder[fillc[col[ch]]++] = ch;
    fl->ncolours = (uint32_t)nc;
    fl->chunk = chunk;
  }
  free(used);
  free(col);
  return nc;
}

/* The largest chunk (NS_CHUNK, then a quarter of it, ...) whose colours hold
 * four chunks each on average, so that threads share every colour's work: a
 * box in box order takes NS_CHUNK (2-4 colours); a mesh in no spatial order
 * ends at single tets, the plain colouring. */
sessile_status ns_build_colours(sessile_fluid *fl) {
  for (uint32_t chunk = NS_CHUNK;; chunk = chunk > 4 ? chunk / 4 : 1) {
    int nc = colour_chunks(fl, chunk);
    SESSILE_CHECK(nc >= 0, SESSILE_ERR_NO_MEMORY, "out of host memory for the assembly's colouring");
    uint64_t nch = ((uint64_t)fl->ntets + chunk - 1) / chunk;
    if (nc > 0 && (nch >= 4 * (uint64_t)nc || chunk == 1)) return SESSILE_OK;
    SESSILE_CHECK(chunk > 1, SESSILE_ERR_INTERNAL, "tet colouring needs more than 256 colours");
  }
}

/* 21 bits of v spread to every third bit. */
static uint64_t spread3(uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffull;
  v = (v | v << 16) & 0x1f0000ff0000ffull;
  v = (v | v << 8) & 0x100f00f00f00f00full;
  v = (v | v << 4) & 0x10c30c30c30c30c3ull;
  v = (v | v << 2) & 0x1249249249249249ull;
  return v;
}

sessile_status ns_order_tets(sessile_fluid *fl) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < fl->nnodes; i++)
    for (int a = 0; a < 3; a++) lo[a] = fmin(lo[a], fl->x[3 * i + a]), hi[a] = fmax(hi[a], fl->x[3 * i + a]);
  double ext = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
  size_t n = (size_t)fl->ntets + 1;
  uint64_t *key = malloc(2 * n * sizeof *key);
  uint32_t *idx = malloc(2 * n * sizeof *idx), *tet = malloc(4 * n * sizeof *tet);
  if (!key || !idx || !tet) {
    free(key), free(idx), free(tet);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for the assembly's order");
  }
  double sc = ext > 0 ? 2097151.0 / ext : 0;
  for (uint32_t t = 0; t < fl->ntets; t++) {
    uint64_t q[3];
    for (int a = 0; a < 3; a++) {
      double c = 0;
      for (int v = 0; v < 4; v++) c += fl->x[3 * (size_t)fl->tet[4 * (size_t)t + v] + a];
      double f = (0.25 * c - lo[a]) * sc;
      q[a] = f > 0 ? (uint64_t)fmin(f, 2097151.0) : 0;
    }
    key[t] = spread3(q[0]) | spread3(q[1]) << 1 | spread3(q[2]) << 2;
    idx[t] = t;
  }
  /* the mesh layer's stable radix sort: equal keys keep the tets' order */
  mesh_sort_u64_idx(key, idx, key + n, idx + n, fl->ntets);
  for (uint32_t t = 0; t < fl->ntets; t++) memcpy(tet + 4 * (size_t)t, fl->tet + 4 * (size_t)idx[t], 4 * sizeof *tet);
  free(fl->tet);
  fl->tet = tet;
  free(key), free(idx);
  return SESSILE_OK;
}
