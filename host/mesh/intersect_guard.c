/* Contact inhibition (docs/intersection.md): a motion may not make the
 * surface cross itself.  Round by round, the pairs that intersect at the
 * current positions but did not at the old ones are found (only triangles
 * that changed since the last round can start intersecting, so only they are
 * queried), and every moved vertex of both triangles of such a pair steps
 * back: halfway, then to its old position (or at once).  A pair of which
 * every vertex is back is as it was, so each round either ends the guard or
 * steps a vertex back: it terminates; the round limit is a safety net that
 * puts every moved vertex back (the old surface, clean by assumption). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "mesh/intersect_internal.h"

#define MAX_ROUNDS 32

static double len3(const double *a, const double *b) {
  double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
  return sqrt(x * x + y * y + z * z);
}

static void corners(const double *pos, const uint32_t *t, double out[9]) {
  for (int i = 0; i < 3; i++) memcpy(out + 3 * i, pos + 3 * t[i], 3 * sizeof *out);
}

sessile_status isect_guard(const uint32_t *tri, uint32_t nf, uint32_t nv, const double *old_pos,
                           double *cur, int halfway, sessile_guard_stats *st) {
  memset(st, 0, sizeof *st);
  double *prop = malloc(((size_t)nv * 3 + 1) * sizeof *prop);
  uint8_t *level = calloc((size_t)nv + 1, 1), *bump = calloc((size_t)nv + 1, 1);
  uint8_t *active = calloc((size_t)nf + 1, 1);
  uint32_t *list = malloc(((size_t)nv + 1) * sizeof *list);
  isect_pairs pairs = {0};
  sessile_status r = SESSILE_OK;
  if (!prop || !level || !bump || !active || !list) {
    r = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory guarding the motion of %u "
                          "vertices", nv);
    goto done;
  }
  memcpy(prop, cur, (size_t)nv * 3 * sizeof *prop);
  /* level: 0 at the proposed position, 1 halfway, 2 back; unmoved vertices
   * count as back. */
  for (uint32_t v = 0; v < nv; v++) {
    const double *o = old_pos + 3 * v, *c = cur + 3 * v;
    level[v] = o[0] == c[0] && o[1] == c[1] && o[2] == c[2] ? 2 : 0;
    if (!level[v]) st->moved++;
  }
  for (uint32_t f = 0; f < nf; f++)
    active[f] = level[tri[3 * f]] < 2 || level[tri[3 * f + 1]] < 2 || level[tri[3 * f + 2]] < 2;
  for (;;) {
    if (st->rounds == MAX_ROUNDS) {
      for (uint32_t v = 0; v < nv; v++)
        if (level[v] < 2) level[v] = 2, memcpy(cur + 3 * v, old_pos + 3 * v, 3 * sizeof *cur);
      st->fallback = 1;
      break;
    }
    st->rounds++;
    if ((r = isect_self_pairs(tri, nf, cur, active, &pairs)) != SESSILE_OK) goto done;
    uint32_t nb = 0;
    for (size_t i = 0; i < pairs.n; i++) {
      const uint32_t *f = tri + 3 * pairs.p[2 * i], *g = tri + 3 * pairs.p[2 * i + 1];
      double a[9], b[9];
      corners(old_pos, f, a), corners(old_pos, g, b);
      if (sessile_triangles_intersect(a, f, b, g)) { /* as it was: not this motion's doing */
        if (st->rounds == 1) st->preexisting++;
        continue;
      }
      for (int c = 0; c < 6; c++) {
        uint32_t v = c < 3 ? f[c] : g[c - 3];
        if (level[v] < 2 && !bump[v]) bump[v] = 1, list[nb++] = v;
      }
    }
    if (!nb) break;
    /* Each vertex steps on its own: the order of the list does not matter. */
    for (uint32_t i = 0; i < nb; i++) {
      uint32_t v = list[i];
      level[v] = halfway ? level[v] + 1 : 2;
      for (int k = 0; k < 3; k++) {
        double o = old_pos[3 * v + k];
        cur[3 * v + k] = level[v] == 2 ? o : o + 0.5 * (prop[3 * v + k] - o);
      }
    }
    /* The triangles of the vertices that stepped back are the only ones
     * whose pairs can have changed. */
    for (uint32_t f = 0; f < nf; f++)
      active[f] = bump[tri[3 * f]] | bump[tri[3 * f + 1]] | bump[tri[3 * f + 2]];
    for (uint32_t i = 0; i < nb; i++) bump[list[i]] = 0;
  }
  for (uint32_t v = 0; v < nv; v++) {
    const double *o = old_pos + 3 * v;
    double p = len3(prop + 3 * v, o);
    st->proposed_cm += p;
    if (p == 0) continue;
    st->kept_cm += len3(cur + 3 * v, o);
    st->held_back += level[v] == 2;
    st->halfway += level[v] == 1;
  }
done:
  free(prop), free(level), free(bump), free(active), free(list), free(pairs.p);
  return r;
}

sessile_status sessile_surface_guard_motion(const sessile_surface *s, double *new_pos, int halfway,
                                            sessile_guard_stats *st) {
  sessile_guard_stats dummy;
  if (!st) st = &dummy;
  SESSILE_CHECK(s && new_pos, SESSILE_ERR_USAGE, "motion guard: no surface or positions given");
  for (size_t k = 0; k < (size_t)s->nf * 3; k++)
    SESSILE_CHECK(s->tri[k] < s->nv, SESSILE_ERR_USAGE,
                  "motion guard: triangle %zu refers to vertex %u of %u", k / 3, s->tri[k], s->nv);
  for (size_t i = 0; i < (size_t)s->nv * 3; i++)
    SESSILE_CHECK(isfinite(new_pos[i]), SESSILE_ERR_NUMERIC,
                  "motion guard: vertex %zu's new position is not finite", i / 3);
  return isect_guard(s->tri, s->nf, s->nv, s->pos, new_pos, halfway, st);
}
