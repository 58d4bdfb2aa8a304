/* Tet colouring for the parallel Navier-Stokes assembly (ns_assemble.c). */
#include <stdlib.h>
#include <string.h>

#include "fem/ns_internal.h"

/* Greedy colouring: no two tets of a colour share a node, so each colour's
 * tets scatter into disjoint block rows without locks. */
sessile_status ns_build_colours(sessile_fluid *fl) {
  enum { W = 4 }; /* up to 256 colours */
  uint64_t *used = calloc((size_t)fl->nnodes * W + 1, sizeof *used);
  uint32_t *col = malloc(((size_t)fl->ntets + 1) * sizeof *col);
  fl->cstart = calloc(257, sizeof *fl->cstart);
  fl->corder = malloc(((size_t)fl->ntets + 1) * sizeof *fl->corder);
  sessile_status s = SESSILE_OK;
  if (!used || !col || !fl->cstart || !fl->corder)
    s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  uint32_t nc = 0;
  for (uint32_t t = 0; s == SESSILE_OK && t < fl->ntets; t++) {
    const uint32_t *v = fl->tet + 4 * (size_t)t;
    int c = -1;
    for (int wd = 0; wd < W && c < 0; wd++) {
      uint64_t m = 0;
      for (int a = 0; a < 4; a++) m |= used[(size_t)v[a] * W + wd];
      if (~m) c = 64 * wd + __builtin_ctzll(~m);
    }
    if (c < 0) {
      s = sessile_error_set(SESSILE_ERR_INTERNAL, "tet colouring needs more than 256 colours");
      break;
    }
    for (int a = 0; a < 4; a++) used[(size_t)v[a] * W + c / 64] |= 1ull << (c % 64);
    col[t] = (uint32_t)c;
    if ((uint32_t)c + 1 > nc) nc = (uint32_t)c + 1;
    fl->cstart[c + 1]++;
  }
  if (s == SESSILE_OK) {
    for (uint32_t c = 0; c < nc; c++) fl->cstart[c + 1] += fl->cstart[c];
    uint32_t fillc[256];
    memcpy(fillc, fl->cstart, sizeof fillc);
    for (uint32_t t = 0; t < fl->ntets; t++) fl->corder[fillc[col[t]]++] = t;
    fl->ncolours = nc;
  }
  free(used);
  free(col);
  return s;
}
