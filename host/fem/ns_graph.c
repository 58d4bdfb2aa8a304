/* The Navier-Stokes block pattern: the node graph (each node with itself and
 * every node sharing a tet) as the 4x4 block CSR pattern of the Jacobian,
 * and each tet's 16 block positions in it (the assembly's scatter targets). */
#include <stdlib.h>
#include <string.h>

#include "fem/ns_internal.h"

static int cmp_u32(const void *a, const void *b) {
  uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
  return (x > y) - (x < y);
}

/* Node graph (each node with itself and every node sharing a tet), as the
 * block pattern, and each tet's 16 block positions. */
sessile_status ns_build_graph(sessile_fluid *fl) {
  uint32_t n = fl->nnodes, nt = fl->ntets;
  uint64_t *cnt = calloc((size_t)n + 1, sizeof *cnt);
  SESSILE_CHECK(cnt, SESSILE_ERR_NO_MEMORY, "out of host memory");
  for (uint64_t t = 0; t < nt; t++)
    for (int a = 0; a < 4; a++) cnt[fl->tet[4 * t + a] + 1] += 4;
  for (uint32_t i = 0; i < n; i++) cnt[i + 1] += cnt[i];
  uint32_t *tmp = malloc((size_t)(cnt[n] ? cnt[n] : 1) * sizeof *tmp);
  uint64_t *fill = malloc((size_t)(n ? n : 1) * sizeof *fill);
  sessile_status s = SESSILE_OK;
  if (!tmp || !fill) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  if (s == SESSILE_OK) {
    memcpy(fill, cnt, (size_t)n * sizeof *fill);
    for (uint64_t t = 0; t < nt; t++)
      for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++) tmp[fill[fl->tet[4 * t + a]]++] = fl->tet[4 * t + b];
    uint64_t nnzb = 0;
    for (uint32_t i = 0; i < n; i++) { /* sort, unique, count */
      uint32_t *row = tmp + cnt[i];
      size_t len = (size_t)(cnt[i + 1] - cnt[i]), u = 0;
      qsort(row, len, sizeof *row, cmp_u32);
      for (size_t k = 0; k < len; k++)
        if (u == 0 || row[k] != row[u - 1]) row[u++] = row[k];
      fill[i] = u;
      nnzb += u;
    }
    s = sessile_bcsr4_alloc(n, n, nnzb, &fl->a);
    if (s == SESSILE_OK) {
      fl->a.rowptr[0] = 0;
      for (uint32_t i = 0; i < n; i++) {
        memcpy(fl->a.col + fl->a.rowptr[i], tmp + cnt[i], (size_t)fill[i] * sizeof *tmp);
        fl->a.rowptr[i + 1] = fl->a.rowptr[i] + fill[i];
      }
      fl->pos = malloc((size_t)nt * 16 * sizeof *fl->pos);
      if (!fl->pos) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
    }
    for (uint64_t t = 0; s == SESSILE_OK && t < nt; t++)
      for (int a = 0; a < 4 && s == SESSILE_OK; a++) {
        uint32_t r = fl->tet[4 * t + a];
        const uint32_t *row = fl->a.col + fl->a.rowptr[r];
        size_t len = (size_t)(fl->a.rowptr[r + 1] - fl->a.rowptr[r]);
        for (int b = 0; b < 4; b++) {
          uint32_t key = fl->tet[4 * t + b];
          const uint32_t *hit = bsearch(&key, row, len, sizeof *row, cmp_u32);
          if (!hit) { /* the pattern holds every pair of a tet: cannot happen */
            s = sessile_error_set(SESSILE_ERR_INTERNAL, "fluid graph: node %u misses neighbour %u of tet %llu",
                                  r, key, (unsigned long long)t);
            break;
          }
          fl->pos[16 * t + 4 * a + b] = (uint32_t)(fl->a.rowptr[r] + (uint64_t)(hit - row));
        }
      }
  }
  free(cnt);
  free(tmp);
  free(fill);
  return s;
}
