/* The rules' half of an SDS step (sds_sim.h): the neighbour lists, the
 * morphogens on the device (§3.3), the rules on the host, growth and the
 * divisions they ask for, and the device's copy brought up to date. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/rng.h"
#include "sds/sds_internal.h"
#include "sds/sds_sim.h"

sessile_status sds_neighbours(sds_sim *s) {
  const sessile_sds *o = &s->o;
  s->morph_lists_set = 0;
  free(s->nbr_off), free(s->nbr);
  s->nbr_off = malloc(((size_t)o->ncells + 1) * sizeof *s->nbr_off);
  s->nbr = malloc(((size_t)o->nedges * 2 + 1) * sizeof *s->nbr);
  SESSILE_CHECK(s->nbr_off && s->nbr, SESSILE_ERR_NO_MEMORY, "sds: out of host memory for %u cells", o->ncells);
  for (uint32_t c = 0; c <= o->ncells; c++) s->nbr_off[c] = o->cell_edge_off[c];
  for (uint32_t c = 0; c < o->ncells; c++)
    for (uint32_t k = o->cell_edge_off[c]; k < o->cell_edge_off[c + 1]; k++) {
      uint32_t e = o->cell_edge[k];
      s->nbr[k] = o->edge[2 * e] == c ? o->edge[2 * e + 1] : o->edge[2 * e];
    }
  return SESSILE_OK;
}

sessile_morph_cells sds_cells_of(const sds_sim *s) {
  sessile_morph_cells c = {(int)s->o.ncells, s->o.x, s->o.r, s->nbr_off, s->nbr, s->o.surface};
  return c;
}

/* After any topology change or growth: derived data, neighbours, the GPU.
 * Without a topology change since the last upload only the radii and masses
 * have changed (the device's x and v are the host's: every step downloads
 * them), and only they go up, with the edges' s_m where they moved. */
sessile_status sds_refresh(sds_sim *s) {
  if (!s->topo_changed) {
    if (s->sm_changed) { /* the oriented growth moved the edges' s_m */
      s->sm_changed = 0;
      SESSILE_CALL(sessile_sds_gpu_update_edge_sm(s->pg, &s->o));
    }
    return sessile_sds_gpu_update_radii(s->pg, &s->o);
  }
  SESSILE_CALL(sds_neighbours(s));
  SESSILE_CALL(sds_axial_assign(s));
  SESSILE_CALL(sessile_sds_gpu_upload(s->pg, &s->o));
  s->topo_changed = 0, s->sm_changed = 0;
  return SESSILE_OK;
}

static sessile_status morphogens(sds_sim *s, const double *src, double dt) {
  if (s->o.nmorph == 0) return SESSILE_OK;
  sessile_morph_cells cells = sds_cells_of(s);
  sessile_morph_coef coef = sessile_sds_model_coef(s->model);
  /* both compute the step bound; the lists go up after a topology change only */
  sessile_status st = s->morph_lists_set ? sessile_morph_gpu_move_cells(s->mg, &cells, &coef)
                                         : sessile_morph_gpu_set_cells(s->mg, &cells, &coef);
  if (st == SESSILE_OK) s->morph_lists_set = 1;
  double bound = sessile_morph_gpu_dt_max(s->mg);
  if (st == SESSILE_ERR_NUMERIC || (st == SESSILE_OK && !(bound > 0)))
    return sds_blowup(s, "two adjacent cells coincide (the morphogens' step bound is 0)");
  SESSILE_CALL(st);
  double n = isfinite(bound) && dt > bound ? ceil(dt / bound * (1 + 1e-9)) : 1;
  if (n > 10000) return sds_blowup(s, "the morphogen step needs %.3g sub-steps (cells too close)", n);
  SESSILE_CALL(sessile_morph_gpu_set_phi(s->mg, s->o.phi, src));
  SESSILE_CALL(sessile_morph_gpu_step(s->mg, dt / n, (int)n));
  return sessile_morph_gpu_get_phi(s->mg, s->o.phi);
}

static void set_mass(sds_sim *s, uint32_t c) { s->o.m[c] = sessile_sds_mass(s->density, s->o.r[c]); }

/* The divisions the rules asked for, in cell order (one request per cell);
 * a division appends its daughter b, so the requests' cell indices stay
 * valid.  A cell whose division was deferred is not tried before its
 * retry time; a vanished gradient draws a seeded direction. */
sessile_status sds_divisions(sds_sim *s, const sessile_sds_divide *req, size_t n) {
  sessile_sds *o = &s->o;
  sessile_status st = SESSILE_OK;
  if (s->retry_cap < o->ncells + n) {
    uint32_t cap = (uint32_t)(2 * (o->ncells + n));
    double *r = realloc(s->retry_at, (size_t)cap * sizeof *r);
    SESSILE_CHECK(r, SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
    for (uint32_t c = s->retry_cap; c < cap; c++) r[c] = -INFINITY;
    s->retry_at = r, s->retry_cap = cap;
  }
  for (size_t i = 0; st == SESSILE_OK && i < n; i++) {
    if (s->time < s->retry_at[req[i].cell]) continue;
    double d[3] = {req[i].dir[0], req[i].dir[1], req[i].dir[2]};
    if (d[0] == 0 && d[1] == 0 && d[2] == 0) {
      /* the gradient vanished: a seeded random direction */
      double z = sessile_rng_range(&s->rng, -1, 1), phi = sessile_rng_range(&s->rng, 0, 2 * SDS_PI), q = sqrt(1 - z * z);
      d[0] = q * cos(phi), d[1] = q * sin(phi), d[2] = z;
    }
    uint32_t c = (uint32_t)req[i].cell, before = o->ncells;
    double at[3] = {o->x[3 * (size_t)c], o->x[3 * (size_t)c + 1], o->x[3 * (size_t)c + 2]}, r = o->r[c];
    st = sds_divide(s, c, d);
    if (st == SESSILE_OK && o->ncells > before) st = sds_divlog_row(s, c, o->ncells - 1, at, r);
    if (st != SESSILE_OK)
      st = sessile_error_set(st, "sds: cell %d cannot divide at t = %g: %s", req[i].cell, s->time,
                             sessile_error_message());
  }
  return st;
}

sessile_status sds_rules(sds_sim *s, double dt) {
  sessile_sds *o = &s->o;
  sessile_morph_cells cells = sds_cells_of(s);
  sessile_sds_actions a;
  memset(&a, 0, sizeof a);
  sessile_status st = sessile_sds_rules_eval(s->model, &cells, o->phi, o->state, s->time, &a);
  if (st == SESSILE_OK) st = morphogens(s, a.produce, dt);
  double *r0 = NULL;
  if (st == SESSILE_OK && s->prm.axial_growth != 0 && !(r0 = malloc((o->ncells + 1) * sizeof *r0)))
    st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory for %u cells", o->ncells);
  if (st == SESSILE_OK) {
    if (r0) memcpy(r0, o->r, o->ncells * sizeof *r0);
    sessile_sds_actions_apply(s->model, &a, dt, o->r, o->phi, o->state);
    for (uint32_t c = 0; c < o->ncells; c++) set_mass(s, c);
    /* before the divisions: the edges are those that grew */
    if (r0 || s->prm.convergent_extension != 0) st = sds_axial_edges_step(s, r0, dt);
  }
  free(r0);
  if (st == SESSILE_OK) st = sds_divisions(s, a.divides, a.ndivides);
  sessile_sds_actions_free(&a);
  SESSILE_CALL(st);
  return sds_refresh(s);
}
