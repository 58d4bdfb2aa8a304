/* The brushes (Coralize §4.1; docs/reef.md, "Placement"): dabs along each
 * stroke, candidates at uniform points of each dab's disc, an entry by the
 * random bias, a size in the entry's range, random rotations; a candidate
 * off the seabed, outside its entry's depth band or overlapping an earlier
 * organism is dropped.  One stream of the seed, consumed in stroke, dab,
 * candidate order with a fixed number of draws per candidate. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "reef/reef_internal.h"
#include "sessile/rng.h"

#define TWO_PI 6.283185307179586
enum { PURPOSE_BRUSH = 0x62727368 };

int reef_site(const sessile_reef_scene *s, const sessile_reef_seabed *b, const sessile_reef_entry *e, double x,
              double y, sessile_reef_placement *p) {
  double z, n[3];
  if (!sessile_reef_seabed_at(b, x, y, &z, n)) return 0;
  double depth = s->sea_level - z;
  if (!(depth >= e->depth[0] && depth <= e->depth[1])) return 0;
  p->pos[0] = x, p->pos[1] = y, p->pos[2] = z, p->depth = depth;
  if (e->follow_terrain) memcpy(p->up, n, sizeof n);
  else p->up[0] = p->up[1] = 0, p->up[2] = 1;
  return 1;
}

void reef_angles(const sessile_reef_entry *e, uint64_t *rng, double angle[3]) {
  for (int a = 0; a < 3; a++) {
    double u = sessile_rng_uniform(rng);
    angle[a] = e->rotate[a] ? TWO_PI * u : 0;
  }
}

/* The dabs of a stroke: its first point, then one every `size` metres of
 * arc length along the polyline, and its last point (once).  An iterator,
 * so a stroke of many points costs one pass. */
typedef struct dab_it {
  int k, seg, ended;
  double run; /* arc length at the start of segment seg */
} dab_it;

static int dab_next(const sessile_reef_stroke *st, dab_it *it, double at[2]) {
  if (it->ended) return 0;
  double want = it->k++ * st->size;
  for (; it->seg + 1 < st->npts; it->seg++) {
    const double *a = st->pts + 2 * it->seg, *c = a + 2;
    double len = hypot(c[0] - a[0], c[1] - a[1]);
    if (want <= it->run + len) {
      double t = len > 0 ? (want - it->run) / len : 0;
      at[0] = a[0] + t * (c[0] - a[0]), at[1] = a[1] + t * (c[1] - a[1]);
      return 1;
    }
    it->run += len;
  }
  /* past the end: the last point, unless the previous dab was it */
  it->ended = 1;
  if (it->k > 1 && want - st->size >= it->run) return 0;
  at[0] = st->pts[2 * st->npts - 2], at[1] = st->pts[2 * st->npts - 1];
  return 1;
}

static double per_dab(const sessile_reef_stroke *st) {
  return st->per_m2 ? st->density * 3.141592653589793 * st->size * st->size : st->density;
}

sessile_status sessile_reef_check(const sessile_reef_scene *s, double *estimate) {
  double n = 0, at[2];
  for (int k = 0; k < s->nstrokes; k++) {
    double d = 0;
    for (dab_it it = {0}; dab_next(&s->strokes[k], &it, at);)
      if (++d > 1e7)
        return sessile_error_set(SESSILE_ERR_USAGE, "brushes[%d].size: the stroke makes over 10^7 dabs: a larger "
                                 "brush or a shorter stroke", k);
    n += d * ceil(per_dab(&s->strokes[k]));
    if (n > SESSILE_REEF_MAX_ORGANISMS)
      return sessile_error_set(SESSILE_ERR_USAGE, "brushes[%d].density: the brushes ask for %.3g organisms, over "
                               "sessile's limit of %d", k, n, SESSILE_REEF_MAX_ORGANISMS);
  }
  if (s->growth_steps > 0) {
    /* growth keeps footprints apart: the seabed holds at most area / (pi rmin^2) */
    double rmin = INFINITY;
    for (int k = 0; k < s->nentries; k++) rmin = fmin(rmin, s->entries[k].size[0]);
    double room = s->extent[0] * s->extent[1] / (3.141592653589793 * rmin * rmin) + n;
    double grown = n * pow(5, s->growth_steps);
    n = fmin(room, grown);
    if (n > SESSILE_REEF_MAX_ORGANISMS)
      return sessile_error_set(SESSILE_ERR_USAGE, "growth.steps: the reef could grow to %.3g organisms, over "
                               "sessile's limit of %d", n, SESSILE_REEF_MAX_ORGANISMS);
  }
  *estimate = n;
  return SESSILE_OK;
}

static uint32_t choose(const sessile_reef_scene *s, double u) {
  double total = 0, run = 0;
  for (int k = 0; k < s->nentries; k++) total += s->entries[k].bias;
  uint32_t last = 0;
  for (int k = 0; k < s->nentries; k++) {
    if (s->entries[k].bias <= 0) continue;
    run += s->entries[k].bias, last = (uint32_t)k;
    if (u * total < run) return (uint32_t)k;
  }
  return last;
}

/* One candidate: always eight draws, accepted or not. */
static sessile_status candidate(const sessile_reef_scene *s, const sessile_reef_seabed *b, reef_grid *g,
                                uint32_t stroke, const double at[2], uint64_t *rng, sessile_reef_placements *pl) {
  const sessile_reef_stroke *st = &s->strokes[stroke];
  double r = st->size * sqrt(sessile_rng_uniform(rng)), th = TWO_PI * sessile_rng_uniform(rng);
  sessile_reef_placement p = {.entry = choose(s, sessile_rng_uniform(rng)), .stroke = stroke,
                              .automatic = st->kind == SESSILE_REEF_AUTOMATIC};
  const sessile_reef_entry *e = &s->entries[p.entry];
  p.size = sessile_rng_range(rng, e->size[0], e->size[1]);
  reef_angles(e, rng, p.angle);
  p.seed = sessile_rng_next(rng);
  double x = at[0] + r * cos(th), y = at[1] + r * sin(th);
  if (!reef_site(s, b, e, x, y, &p) || reef_grid_overlaps(g, pl, x, y, p.size)) return SESSILE_OK;
  SESSILE_CALL(reef_push(pl, &p));
  return reef_grid_add(g, pl, pl->n - 1);
}

sessile_status sessile_reef_place(const sessile_reef_scene *s, const sessile_reef_seabed *b, uint64_t seed,
                                  sessile_reef_placements *out) {
  double estimate;
  SESSILE_CALL(sessile_reef_check(s, &estimate));
  memset(out, 0, sizeof *out);
  reef_grid g;
  SESSILE_CALL(reef_grid_init(&g, s));
  uint64_t rng = sessile_rng_stream(seed, PURPOSE_BRUSH);
  sessile_status st = SESSILE_OK;
  double at[2];
  for (uint32_t k = 0; k < (uint32_t)s->nstrokes && st == SESSILE_OK; k++) {
    double m = per_dab(&s->strokes[k]);
    for (dab_it it = {0}; st == SESSILE_OK && dab_next(&s->strokes[k], &it, at);) {
      /* a fractional count: one more candidate with that probability */
      int n = (int)floor(m) + (sessile_rng_uniform(&rng) < m - floor(m));
      for (int c = 0; c < n && st == SESSILE_OK; c++) st = candidate(s, b, &g, k, at, &rng, out);
    }
  }
  reef_grid_free(&g);
  if (st != SESSILE_OK) sessile_reef_placements_free(out);
  return st;
}
