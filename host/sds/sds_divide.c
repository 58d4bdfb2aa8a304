/* Cell division through the complex (§3.1.1; sds_sim.h): the organism's
 * cells and tets copied into a growable complex, TetGen's division, the
 * complex taken back when it is valid, masses, radii and morphogens shared
 * between the daughters. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sds/sds_internal.h"
#include "sds/sds_sim.h"

/* The organism's x and tet as a growable complex (copies). */
sessile_status sds_complex_of(const sessile_sds *o, sessile_sds_topo_complex *cx) {
  memset(cx, 0, sizeof *cx);
  cx->x = malloc((size_t)o->ncells * 3 * sizeof *cx->x);
  cx->tet = malloc((size_t)o->ntets * 4 * sizeof *cx->tet);
  if (!cx->x || !cx->tet) {
    sessile_sds_topo_complex_free(cx);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory for %u tets", o->ntets);
  }
  memcpy(cx->x, o->x, (size_t)o->ncells * 3 * sizeof *cx->x);
  memcpy(cx->tet, o->tet, (size_t)o->ntets * 4 * sizeof *cx->tet);
  cx->nv = o->ncells, cx->nt = o->ntets;
  return SESSILE_OK;
}

/* Takes the complex back: x and tets, s_m of kept tets by tet_from (new: 0,
 * so that rebuild gives them rest sizes from the radii). */
sessile_status sds_take_complex(sds_sim *s, const sessile_sds_topo_complex *cx, const uint32_t *tet_from) {
  sessile_sds *o = &s->o;
  uint32_t old_cells = o->ncells;
  SESSILE_CALL(sessile_sds_reserve(o, cx->nv, cx->nt));
  double *sm = malloc(((size_t)cx->nt + 1) * sizeof *sm);
  SESSILE_CHECK(sm, SESSILE_ERR_NO_MEMORY, "sds: out of host memory for %u tets", cx->nt);
  for (uint32_t t = 0; t < cx->nt; t++) sm[t] = tet_from[t] == SESSILE_SDS_TOPO_NEW_TET ? 0 : o->tet_sm[tet_from[t]];
  memcpy(o->tet_sm, sm, (size_t)cx->nt * sizeof *sm);
  free(sm);
  memcpy(o->x, cx->x, (size_t)cx->nv * 3 * sizeof *o->x);
  memcpy(o->tet, cx->tet, (size_t)cx->nt * 4 * sizeof *o->tet);
  o->ncells = cx->nv, o->ntets = cx->nt;
  (void)old_cells;
  s->topo_changed = 1;
  return sessile_sds_rebuild_oriented(o, SESSILE_SDS_NEW_UNIT);
}

/* Divides cell c toward dir: mass halved between the daughters, radii from
 * the masses (§3.1.1), morphogens halved, state, velocity copied. */
sessile_status sds_divide(sds_sim *s, uint32_t c, const double dir[3]) {
  sessile_sds_topo_complex cx;
  SESSILE_CALL(sds_complex_of(&s->o, &cx));
  sessile_sds_topo_division dv;
  memset(&dv, 0, sizeof dv);
  double eps_max = 0.5 * s->o.r[c];
  sessile_status st = sessile_sds_topo_divide(&cx, c, dir, eps_max, &dv);
  /* slivers elsewhere, inverted before and unchanged, do not count against
   * it: one lasting sliver had stopped every division (the rock model: 29 622
   * put off from t = 320; docs/sds.md "The loop") */
  sessile_status kept = st == SESSILE_OK ? sessile_sds_topo_check_kept(s->o.x, s->o.ntets, s->o.tet, &cx, dv.tet_from)
                                         : SESSILE_OK;
  if (kept == SESSILE_ERR_NO_MEMORY) st = kept; /* a failure, not an invalid division to put off */
  int valid = st == SESSILE_OK && kept == SESSILE_OK;
  if (st == SESSILE_ERR_UNSUPPORTED || st == SESSILE_ERR_NUMERIC || (st == SESSILE_OK && !valid)) {
    /* TetGen cannot mesh c's hull without a new point (and the cone
     * fallback failed), or the division would leave an invalid complex (a
     * tet of its own inverted): the division waits for a later step, when
     * the cells have moved */
    free(dv.tet_from);
    sessile_sds_topo_complex_free(&cx);
    s->st->deferred++;
    /* TetGen and the check cost milliseconds: not again for 100 steps */
    if (c < s->retry_cap) s->retry_at[c] = s->time + 100 * s->dt;
    return SESSILE_OK;
  }
  if (st == SESSILE_OK) st = sds_take_complex(s, &cx, dv.tet_from);
  free(dv.tet_from);
  sessile_sds_topo_complex_free(&cx);
  SESSILE_CALL(st);
  sessile_sds *o = &s->o;
  uint32_t a = dv.a, b = dv.b;
  double m = 0.5 * o->m[a];
  o->m[a] = o->m[b] = m;
  o->r[a] = o->r[b] = cbrt(3 * m / (4 * SDS_PI * s->density));
  for (int k = 0; k < 3; k++) o->v[3 * b + k] = o->v[3 * a + k];
  for (uint32_t k = 0; k < o->nmorph; k++) o->phi[(size_t)a * o->nmorph + k] *= 0.5,
                                        o->phi[(size_t)b * o->nmorph + k] = o->phi[(size_t)a * o->nmorph + k];
  for (uint32_t k = 0; k < o->nstate; k++) o->state[(size_t)b * o->nstate + k] = o->state[(size_t)a * o->nstate + k];
  o->attract[b] = -1;
  /* a growing tip is a lineage: daughter a (the mother's index, on the
   * surface) stays the tip, b starts as an ordinary cell; a tip dividing
   * inward so leaves a cell below itself, the pressure that pushes it out
   * (§3.6; docs/sds_rules.md, "Tips") */
  if (s->tip_state >= 0) o->state[(size_t)b * o->nstate + (uint32_t)s->tip_state] = 0;
  if (s->birth_state >= 0)
    o->state[(size_t)a * o->nstate + (uint32_t)s->birth_state] = o->state[(size_t)b * o->nstate + (uint32_t)s->birth_state] = o->r[a];
  /* the daughters' edges and tets are new: rest sizes from the new radii */
  s->st->divisions++, s->div_interval++;
  return SESSILE_OK;
}
