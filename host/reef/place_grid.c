/* The footprint grid (reef_internal.h): no two organisms' discs overlap
 * (docs/reef.md, "Placement").  Cells of 2 rmax, so a query looks at the
 * 3x3 cells around the disc's own. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "reef/reef_internal.h"

#define NONE UINT32_MAX

sessile_status reef_grid_init(reef_grid *g, const sessile_reef_scene *s) {
  memset(g, 0, sizeof *g);
  for (int k = 0; k < s->nentries; k++) g->rmax = fmax(g->rmax, s->entries[k].size[1]);
  g->cell = 2 * g->rmax;
  /* at most 2^22 cells: a finer grid than the organisms' spacing buys nothing */
  while ((s->extent[0] / g->cell + 1) * (s->extent[1] / g->cell + 1) > 4194304.0) g->cell *= 2;
  g->gx = (uint32_t)(s->extent[0] / g->cell) + 1, g->gy = (uint32_t)(s->extent[1] / g->cell) + 1;
  g->head = malloc((size_t)g->gx * g->gy * sizeof *g->head);
  SESSILE_CHECK(g->head, SESSILE_ERR_NO_MEMORY, "out of host memory for the placement grid");
  memset(g->head, 0xFF, (size_t)g->gx * g->gy * sizeof *g->head);
  return SESSILE_OK;
}

static uint32_t cell_of(const reef_grid *g, double v, uint32_t n) {
  double c = floor(v / g->cell);
  return c < 0 ? 0 : c >= n ? n - 1 : (uint32_t)c;
}

sessile_status reef_grid_add(reef_grid *g, const sessile_reef_placements *pl, uint32_t k) {
  if (k >= g->cap) {
    uint32_t cap = pl->cap > k ? pl->cap : k + 1;
    uint32_t *n = realloc(g->next, (size_t)cap * sizeof *n);
    SESSILE_CHECK(n, SESSILE_ERR_NO_MEMORY, "out of host memory for the placement grid");
    g->next = n, g->cap = cap;
  }
  const double *x = pl->p[k].pos;
  size_t c = (size_t)cell_of(g, x[1], g->gy) * g->gx + cell_of(g, x[0], g->gx);
  g->next[k] = g->head[c], g->head[c] = k;
  return SESSILE_OK;
}

int reef_grid_overlaps(const reef_grid *g, const sessile_reef_placements *pl, double x, double y, double r) {
  double reach = r + g->rmax;
  uint32_t i0 = cell_of(g, x - reach, g->gx), i1 = cell_of(g, x + reach, g->gx);
  uint32_t j0 = cell_of(g, y - reach, g->gy), j1 = cell_of(g, y + reach, g->gy);
  for (uint32_t j = j0; j <= j1; j++)
    for (uint32_t i = i0; i <= i1; i++)
      for (uint32_t k = g->head[(size_t)j * g->gx + i]; k != NONE; k = g->next[k]) {
        const sessile_reef_placement *p = &pl->p[k];
        double dx = p->pos[0] - x, dy = p->pos[1] - y, rr = p->size + r;
        if (dx * dx + dy * dy < rr * rr) return 1;
      }
  return 0;
}

void reef_grid_free(reef_grid *g) {
  free(g->head), free(g->next);
  memset(g, 0, sizeof *g);
}

sessile_status reef_push(sessile_reef_placements *pl, const sessile_reef_placement *p) {
  if (pl->n == pl->cap) {
    uint32_t cap = pl->cap ? 2 * pl->cap : 256;
    sessile_reef_placement *q = realloc(pl->p, (size_t)cap * sizeof *q);
    SESSILE_CHECK(q, SESSILE_ERR_NO_MEMORY, "out of host memory for %u placements", cap);
    pl->p = q, pl->cap = cap;
  }
  pl->p[pl->n++] = *p;
  return SESSILE_OK;
}

void sessile_reef_placements_free(sessile_reef_placements *p) {
  if (p) free(p->p), memset(p, 0, sizeof *p);
}
