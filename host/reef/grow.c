/* Reef growth (Coralize §4.2; docs/reef.md, "Growth").  One step: every
 * organism alive at the step's start proposes its four cardinal neighbours
 * at the spacing (+x, -x, +y, -y); a proposal survives when it is on the
 * seabed, in its entry's depth band and clear of every organism of the
 * step's start.  The survivors are then taken in the order of (y, x, entry,
 * seed) -- a property of the set, not of the loop that made it -- each
 * accepted unless it overlaps one accepted before it.  The child keeps its
 * parent's entry and size; its seed mixes the parent's with the step and
 * direction, so it too is independent of order. */
#include <stdlib.h>
#include <string.h>
#include "reef/reef_internal.h"
#include "sessile/rng.h"

static int by_site(const void *pa, const void *pb) {
  const sessile_reef_placement *a = pa, *b = pb;
  if (a->pos[1] != b->pos[1]) return a->pos[1] < b->pos[1] ? -1 : 1;
  if (a->pos[0] != b->pos[0]) return a->pos[0] < b->pos[0] ? -1 : 1;
  if (a->entry != b->entry) return a->entry < b->entry ? -1 : 1;
  return a->seed < b->seed ? -1 : a->seed > b->seed;
}

sessile_status sessile_reef_grow_step(const sessile_reef_scene *s, const sessile_reef_seabed *b, int step,
                                      sessile_reef_placements *pl, uint32_t *added) {
  static const double dir[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  uint32_t n0 = pl->n;
  *added = 0;
  reef_grid g;
  SESSILE_CALL(reef_grid_init(&g, s));
  sessile_reef_placements cand = {0};
  sessile_status st = SESSILE_OK;
  for (uint32_t k = 0; k < n0 && st == SESSILE_OK; k++) st = reef_grid_add(&g, pl, k);
  for (uint32_t k = 0; k < n0 && st == SESSILE_OK; k++)
    for (int d = 0; d < 4 && st == SESSILE_OK; d++) {
      const sessile_reef_placement *par = &pl->p[k];
      const sessile_reef_entry *e = &s->entries[par->entry];
      sessile_reef_placement c = {.entry = par->entry, .stroke = UINT32_MAX, .automatic = 1, .size = par->size};
      c.seed = sessile_rng_mix(par->seed ^ sessile_rng_mix(((uint64_t)step << 2 | (uint64_t)d) + 1));
      double x = par->pos[0] + s->spacing * dir[d][0], y = par->pos[1] + s->spacing * dir[d][1];
      if (!reef_site(s, b, e, x, y, &c) || reef_grid_overlaps(&g, pl, x, y, c.size)) continue;
      uint64_t rng = c.seed;
      reef_angles(e, &rng, c.angle);
      st = reef_push(&cand, &c);
    }
  if (st == SESSILE_OK && cand.n) qsort(cand.p, cand.n, sizeof *cand.p, by_site);
  for (uint32_t k = 0; k < cand.n && st == SESSILE_OK; k++) {
    const sessile_reef_placement *c = &cand.p[k];
    if (reef_grid_overlaps(&g, pl, c->pos[0], c->pos[1], c->size)) continue;
    st = reef_push(pl, c);
    if (st == SESSILE_OK) st = reef_grid_add(&g, pl, pl->n - 1), ++*added;
  }
  sessile_reef_placements_free(&cand);
  reef_grid_free(&g);
  return st;
}
