/* The SDS loop (sessile/sds_run.h, docs/sds.md "The loop").  One step:
 *   1. physics: one integrator step on the GPU (step control inside);
 *   2. inversions: tets with volume <= 0 after the step are found on the GPU;
 *      the first inversion time among them (linear motion over the step,
 *      §3.1.2) rewinds every cell to that time, the tet's case-1 or case-2
 *      transformation is applied (host, TetGen) and the step goes on;
 *   3. morphogens: explicit Euler on the GPU, sub-stepped below its bound;
 *   4. rules: evaluated on the host in cell order, then sets, growth (r, m)
 *      and divisions (host, TetGen) in cell order.
 * Same model, seed and device: the same bytes. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/io.h"
#include "sessile/rng.h"
#include "sessile/sds.h"
#include "sessile/sds_process.h"
#include "sessile/sds_run.h"
#include "sessile/sds_topo.h"
#include "sds/sds_checkpoint.h"
#include "sds/sds_surface_file.h"

typedef struct sim {
  const char *text;           /* the model */
  sessile_sds_model *model;
  sessile_sds o;
  sessile_sds_params p;
  sessile_sds_run_params prm; /* the parameter table's values (sds_params.c) */
  sessile_sds_gpu *pg;
  sessile_morph_gpu *mg;
  sessile_surface rock;       /* the obstacle, when the model has one */
  double attractor[3];
  double density;
  uint32_t *nbr_off, *nbr;    /* cell neighbours (from the edges) */
  double *xprev;              /* positions before the step (rewind) */
  double time, dt;
  int stalled;                /* steps in a row that were rewound to their start */
  double *retry_at;           /* per cell: a deferred division is not tried again before this time */
  uint32_t retry_cap;
  uint64_t *sliver;           /* the repairs' backoff: per failed inverted tet (FNV-1a of its cells),
                                 failures in a row, the step before which it is not tried again */
  uint32_t nsliver, sliver_cap;
  int topo_changed;           /* the complex changed since the last upload (refresh uploads it whole) */
  int morph_lists_set;        /* the morphogen kernel has the current neighbour lists (neighbours() clears) */
  uint64_t rng;
  int tip_state;              /* state index of `tip`, -1 none */
  int birth_state;            /* state index of `birth_radius` (the loop keeps it), -1 none */
  sessile_sds_run_stats *st;
  uint64_t div_interval, inv_interval; /* counts since the last record */
  uint64_t key;               /* sds_ckpt_key of the model and options */
  uint64_t seed;              /* the run's seed (division directions, the start's jitter) */
  double c0[3], size0;        /* the starting organism's centroid and size */
  int frame;                  /* the next frame to write */
  uint64_t steps_frame;       /* steps since the last frame */
  int resumed;                /* restored from a checkpoint */
  double step_t0;             /* the time at the start of the step being made */
  double t_end;               /* resolved: the option or the model's */
  int frames;
  char *steplog;              /* sds/steps.csv rows not yet appended (flushed before each checkpoint) */
  size_t steplog_len, steplog_cap;
} sim;

static const double PI = 3.14159265358979323846;

/* --- model parameters -------------------------------------------------------- */
static double param1(const sessile_sds_model *m, const char *name, double def) {
  const sessile_sds_param *q = sessile_sds_model_param_find(m, name);
  return q && q->nvalues >= 1 ? q->values[0] : def;
}

/* The physics from the parameter table's values and the model's scene
 * (box, rock, attractor: vectors the table does not hold). */
static sessile_status read_physics(sim *s, const char *where) {
  const sessile_sds_model *m = s->model;
  const sessile_sds_run_params *q = &s->prm;
  sessile_sds_params_default(&s->p);
  s->p.k_edge = q->edge_stiffness;
  s->p.k_vol = q->volume_stiffness;
  s->p.surface_mult = q->surface_multiplier;
  s->p.damp_vol = q->damping;
  s->p.damp_visc = q->viscosity;
  s->p.gravity = q->gravity;
  s->p.dt = q->dt;
  s->p.max_move = q->max_move;
  s->p.stable_safety = q->stable_safety;
  s->density = q->density;
  s->p.self_collide = q->self_collide;
  const sessile_sds_param *box = sessile_sds_model_param_find(m, "box");
  if (box) {
    SESSILE_CHECK(box->nvalues == 6, SESSILE_ERR_USAGE, "%s:%d: box needs 6 values: xmin ymin zmin xmax ymax zmax",
                  where, box->line);
    s->p.box = 1;
    for (int k = 0; k < 3; k++) {
      s->p.box_lo[k] = box->values[k], s->p.box_hi[k] = box->values[3 + k];
      SESSILE_CHECK(s->p.box_lo[k] < s->p.box_hi[k], SESSILE_ERR_USAGE, "%s:%d: the box is empty along axis %d", where,
                    box->line, k);
    }
  }
  const sessile_sds_param *rock = sessile_sds_model_param_find(m, "rock");
  if (rock) {
    SESSILE_CHECK(rock->nvalues == 4 && rock->values[3] > 0, SESSILE_ERR_USAGE,
                  "%s:%d: rock needs 4 values: centre x y z and a radius > 0", where, rock->line);
    SESSILE_CALL(sessile_surface_icosphere(4, rock->values[3], rock->values, &s->rock));
    s->p.obstacle.nv = s->rock.nv, s->p.obstacle.nf = s->rock.nf;
    s->p.obstacle.pos = s->rock.pos, s->p.obstacle.tri = s->rock.tri;
  }
  const sessile_sds_param *att = sessile_sds_model_param_find(m, "attractor");
  if (att) {
    SESSILE_CHECK(att->nvalues == 4, SESSILE_ERR_USAGE, "%s:%d: attractor needs 4 values: x y z strength", where,
                  att->line);
    memcpy(s->attractor, att->values, sizeof s->attractor);
    s->p.nattract = 1, s->p.attract_pos = s->attractor, s->p.k_attract = att->values[3];
  }
  return SESSILE_OK;
}

static sessile_status blowup(sim *s, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* --- neighbours and morphogens -------------------------------------------- */
static sessile_status neighbours(sim *s) {
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

static sessile_morph_cells cells_of(const sim *s) {
  sessile_morph_cells c = {(int)s->o.ncells, s->o.x, s->o.r, s->nbr_off, s->nbr, s->o.surface};
  return c;
}

/* After any topology change or growth: derived data, neighbours, the GPU.
 * Without a topology change since the last upload only the radii and masses
 * have changed (the device's x and v are the host's: every step downloads
 * them), and only they go up. */
static sessile_status refresh(sim *s) {
  if (!s->topo_changed) return sessile_sds_gpu_update_radii(s->pg, &s->o);
  SESSILE_CALL(neighbours(s));
  SESSILE_CALL(sessile_sds_gpu_upload(s->pg, &s->o));
  s->topo_changed = 0;
  return SESSILE_OK;
}

static sessile_status morphogens(sim *s, const double *src, double dt) {
  if (s->o.nmorph == 0) return SESSILE_OK;
  sessile_morph_cells cells = cells_of(s);
  sessile_morph_coef coef = sessile_sds_model_coef(s->model);
  /* both compute the step bound; the lists go up after a topology change only */
  sessile_status st = s->morph_lists_set ? sessile_morph_gpu_move_cells(s->mg, &cells, &coef)
                                         : sessile_morph_gpu_set_cells(s->mg, &cells, &coef);
  if (st == SESSILE_OK) s->morph_lists_set = 1;
  double bound = sessile_morph_gpu_dt_max(s->mg);
  if (st == SESSILE_ERR_NUMERIC || (st == SESSILE_OK && !(bound > 0)))
    return blowup(s, "two adjacent cells coincide (the morphogens' step bound is 0)");
  SESSILE_CALL(st);
  double n = isfinite(bound) && dt > bound ? ceil(dt / bound * (1 + 1e-9)) : 1;
  if (n > 10000) return blowup(s, "the morphogen step needs %.3g sub-steps (cells too close)", n);
  SESSILE_CALL(sessile_morph_gpu_set_phi(s->mg, s->o.phi, src));
  SESSILE_CALL(sessile_morph_gpu_step(s->mg, dt / n, (int)n));
  return sessile_morph_gpu_get_phi(s->mg, s->o.phi);
}

/* --- topology through the complex ------------------------------------------ */
/* The organism's x and tet as a growable complex (copies). */
static sessile_status complex_of(const sessile_sds *o, sessile_sds_topo_complex *cx) {
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
static sessile_status take_complex(sim *s, const sessile_sds_topo_complex *cx, const uint32_t *tet_from) {
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

static void set_mass(sim *s, uint32_t c) { s->o.m[c] = s->density * 4.0 / 3.0 * PI * pow(s->o.r[c], 3); }

/* Divides cell c toward dir: mass halved between the daughters, radii from
 * the masses (§3.1.1), morphogens halved, state, velocity copied. */
static sessile_status divide(sim *s, uint32_t c, const double dir[3]) {
  sessile_sds_topo_complex cx;
  SESSILE_CALL(complex_of(&s->o, &cx));
  sessile_sds_topo_division dv;
  memset(&dv, 0, sizeof dv);
  double eps_max = 0.5 * s->o.r[c];
  sessile_status st = sessile_sds_topo_divide(&cx, c, dir, eps_max, &dv);
  /* slivers elsewhere, inverted before and unchanged, do not count against
   * it: one lasting sliver had stopped every division (the rock model: 29 622
   * put off from t = 320; docs/sds.md "The loop") */
  int valid = st == SESSILE_OK &&
              sessile_sds_topo_check_kept(s->o.x, s->o.ntets, s->o.tet, &cx, dv.tet_from) == SESSILE_OK;
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
  if (st == SESSILE_OK) st = take_complex(s, &cx, dv.tet_from);
  free(dv.tet_from);
  sessile_sds_topo_complex_free(&cx);
  SESSILE_CALL(st);
  sessile_sds *o = &s->o;
  uint32_t a = dv.a, b = dv.b;
  double m = 0.5 * o->m[a];
  o->m[a] = o->m[b] = m;
  o->r[a] = o->r[b] = cbrt(3 * m / (4 * PI * s->density));
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

/* --- repair ----------------------------------------------------------------- */
/* Inverted tets that no transformation removed (they began the step inverted,
 * or their transformation was refused): the cavity around them is
 * re-tetrahedralised (sessile_sds_topo_repair) and the organism takes it if
 * the whole complex is then valid; else the volume springs go on resisting
 * (docs/sds.md, "The loop").  Without it one lasting sliver stopped every
 * division for the rest of a run (they wait for a valid complex). */
/* The backoff table's entry of the inverted tet with hash h, or nsliver. */
static uint32_t sliver_find(const sim *s, uint64_t h) {
  uint32_t e = 0;
  while (e < s->nsliver && s->sliver[3 * e] != h) e++;
  return e;
}

static sessile_status repair(sim *s) {
  sessile_sds *o = &s->o;
  uint32_t *bad = malloc(((size_t)o->ntets + 1) * sizeof *bad), nbad = 0, ntry = 0;
  uint64_t *hb = malloc(((size_t)o->ntets + 1) * sizeof *hb);
  if (!bad || !hb) {
    free(bad), free(hb);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
  }
  /* the inverted tets, each named by its cells (cell indices outlive the
   * renumbering of tets by a division elsewhere): an FNV-1a of its sorted
   * cells */
  for (uint32_t t = 0; t < o->ntets; t++) {
    const uint32_t *v = o->tet + 4 * (size_t)t;
    if (sessile_sds_topo_volume(o->x + 3 * (size_t)v[0], o->x + 3 * (size_t)v[1], o->x + 3 * (size_t)v[2],
                                o->x + 3 * (size_t)v[3]) > 0)
      continue;
    uint32_t q[4] = {v[0], v[1], v[2], v[3]};
    for (int i = 1; i < 4; i++)
      for (int j = i; j > 0 && q[j - 1] > q[j]; j--) {
        uint32_t w = q[j];
        q[j] = q[j - 1], q[j - 1] = w;
      }
    uint64_t h = 14695981039346656037ull;
    for (int i = 0; i < 4; i++) h = (h ^ q[i]) * 1099511628211ull;
    hb[nbad] = h, bad[nbad++] = t;
  }
  /* The backoff, per inverted tet: after k failed tries in a row it waits
   * 2^k steps (at most 128) before the next.  A sliver can last thousands
   * of steps, and a try copies and checks the whole complex and calls
   * TetGen up to three times: tried at every step it was 40 % of the rock
   * model's run, and keyed on the whole set of inverted tets (which changes
   * every few steps late in that run, with 40 slivers) a try every 8 steps
   * still cost 12 ms each, 2.5 ms per step.  A try takes the tets that are
   * due, alone, so that a new sliver is not held back by old ones that
   * TetGen cannot mesh.  Entries of tets no longer inverted are dropped. */
  uint32_t keep = 0;
  for (uint32_t e = 0; e < s->nsliver; e++) {
    uint32_t i = 0;
    while (i < nbad && hb[i] != s->sliver[3 * e]) i++;
    if (i < nbad) memmove(s->sliver + 3 * keep++, s->sliver + 3 * e, 3 * sizeof *s->sliver);
  }
  s->nsliver = keep;
  for (uint32_t i = 0; i < nbad; i++) {
    uint32_t e = sliver_find(s, hb[i]);
    if (e == s->nsliver || s->st->steps >= s->sliver[3 * e + 2]) hb[ntry] = hb[i], bad[ntry++] = bad[i];
  }
  sessile_status st = SESSILE_OK;
  if (ntry) {
    sessile_sds_topo_complex cx;
    sessile_sds_topo_transform tr;
    memset(&tr, 0, sizeof tr);
    st = complex_of(o, &cx);
    sessile_status rst = st == SESSILE_OK ? sessile_sds_topo_repair(&cx, bad, ntry, &tr) : st;
    /* inverted tets left out of the try may stay as they were */
    int ok = st == SESSILE_OK && rst == SESSILE_OK &&
             sessile_sds_topo_check_kept(o->x, o->ntets, o->tet, &cx, tr.tet_from) == SESSILE_OK;
    if (ok) {
      st = take_complex(s, &cx, tr.tet_from);
      if (st == SESSILE_OK) s->st->repairs++;
    } else if (st == SESSILE_OK && rst == SESSILE_ERR_NO_MEMORY)
      st = rst;
    else
      for (uint32_t i = 0; i < ntry && st == SESSILE_OK; i++) {
        uint32_t e = sliver_find(s, hb[i]);
        if (e == s->nsliver) {
          if (s->nsliver == s->sliver_cap) {
            uint32_t cap = s->sliver_cap ? 2 * s->sliver_cap : 16;
            uint64_t *w = realloc(s->sliver, 3 * (size_t)cap * sizeof *w);
            if (!w) {
              st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
              break;
            }
            s->sliver = w, s->sliver_cap = cap;
          }
          s->sliver[3 * e] = hb[i], s->sliver[3 * e + 1] = 0, s->nsliver++;
        }
        uint64_t k = ++s->sliver[3 * e + 1];
        s->sliver[3 * e + 2] = s->st->steps + (1u << (k < 7 ? k : 7));
      }
    free(tr.tet_from);
    sessile_sds_topo_complex_free(&cx);
  }
  free(bad), free(hb);
  return st;
}

/* --- inversions (§3.1.2) ---------------------------------------------------- */
/* The tets inverted by the last step: rewind every cell to the first
 * inversion time among them and transform that tet; the others are not
 * inverted at that time and are found again by the next step's check. */
static sessile_status inversions(sim *s, int *handled, double *frac) {
  *handled = 0;
  *frac = 1;
  uint32_t *list = NULL, n = 0;
  SESSILE_CALL(sessile_sds_gpu_inverted(s->pg, &list, &n));
  if (n == 0) {
    free(list);
    return SESSILE_OK;
  }
  sessile_sds *o = &s->o;
  double best = INFINITY;
  uint32_t bt = UINT32_MAX;
  sessile_sds_topo_inversion binv;
  memset(&binv, 0, sizeof binv);
  for (uint32_t i = 0; i < n; i++) {
    const uint32_t *t = o->tet + 4 * (size_t)list[i];
    double p[12], q[12];
    for (int k = 0; k < 4; k++)
      for (int a = 0; a < 3; a++) p[3 * k + a] = s->xprev[3 * (size_t)t[k] + a], q[3 * k + a] = o->x[3 * (size_t)t[k] + a];
    sessile_sds_topo_inversion inv;
    if (sessile_sds_topo_inversion_time(p, q, 0, 1, &inv) && inv.s < best) best = inv.s, bt = list[i], binv = inv;
  }
  free(list);
  if (bt == UINT32_MAX) {
    /* inverted, but with no sign change over the step: they began the step
     * inverted, slivers a re-tetrahedralisation made flat to rounding or
     * ones an earlier step left.  Their volume springs push them back open
     * (E grows with (V - R')^2 for V < 0 too); the step stands and they
     * are counted (docs/sds.md, "The loop"). */
    s->st->slivers += n;
    return repair(s);
  }
  /* the transformation is made just before the flat moment, so that the
   * flat tet's four cells are not coplanar for TetGen (relative 1e-6 of the
   * step; the paper makes it at the moment itself) */
  best *= 1 - 1e-6;
  /* rewind to the inversion time (linear motion over the step) */
  size_t n3 = 3 * (size_t)o->ncells;
  double *xnew = malloc(n3 * sizeof *xnew);
  SESSILE_CHECK(xnew, SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
  memcpy(xnew, o->x, n3 * sizeof *xnew);
  for (size_t i = 0; i < n3; i++) o->x[i] = s->xprev[i] + best * (xnew[i] - s->xprev[i]);
  sessile_sds_topo_complex cx;
  sessile_status st = complex_of(o, &cx);
  sessile_sds_topo_transform tr;
  memset(&tr, 0, sizeof tr);
  sessile_status tst = SESSILE_OK; /* the transformation's own answer */
  if (st == SESSILE_OK) tst = sessile_sds_topo_apply_inversion(&cx, bt, &binv, &tr);
  /* the result must be a valid complex before the organism takes it (an
   * inverted sliver elsewhere, or a covering tet that overlaps the body,
   * would otherwise spread): a refusal like the transformation's own */
  if (st == SESSILE_OK && tst == SESSILE_OK && sessile_sds_topo_check(cx.nv, cx.x, cx.nt, cx.tet, 0, NULL) != SESSILE_OK)
    tst = SESSILE_ERR_UNSUPPORTED;
  if (st == SESSILE_OK && tst == SESSILE_OK) st = take_complex(s, &cx, tr.tet_from);
  free(tr.tet_from);
  sessile_sds_topo_complex_free(&cx);
  if (st == SESSILE_OK && tst != SESSILE_OK && tst != SESSILE_ERR_UNSUPPORTED && tst != SESSILE_ERR_NUMERIC) st = tst;
  if (st == SESSILE_OK && tst != SESSILE_OK) {
    /* No transformation for this one (both v and f on the surface, a ridge,
     * a hull TetGen cannot mesh without a new point): the paper leaves such
     * cases open.  The step stands as it was and the tet's volume spring
     * (E grows with (V - R')^2 for V < 0 too) pushes it back open; counted
     * as resisted (docs/sds.md, "The loop"). */
    memcpy(o->x, xnew, n3 * sizeof *xnew);
    s->st->resisted++;
    free(xnew);
    return repair(s);
  }
  free(xnew);
  if (st != SESSILE_OK)
    return sessile_error_set(st, "sds: the inversion of tet %u at t = %g could not be handled: %s", bt, s->time,
                             sessile_error_message());
  s->st->inversions++, s->inv_interval++;
  *handled = 1;
  *frac = best;
  return SESSILE_OK;
}

/* --- rules ----------------------------------------------------------------- */
static sessile_status rules(sim *s, double dt) {
  sessile_sds *o = &s->o;
  sessile_morph_cells cells = cells_of(s);
  sessile_sds_actions a;
  memset(&a, 0, sizeof a);
  sessile_status st = sessile_sds_rules_eval(s->model, &cells, o->phi, o->state, s->time, &a);
  if (st == SESSILE_OK) st = morphogens(s, a.produce, dt);
  if (st == SESSILE_OK) {
    sessile_sds_actions_apply(s->model, &a, dt, o->r, o->phi, o->state);
    for (uint32_t c = 0; c < o->ncells; c++) set_mass(s, c);
  }
  /* divisions in cell order; a division appends its daughter b, so the
   * requests' cell indices stay valid */
  if (st == SESSILE_OK && s->retry_cap < o->ncells + a.ndivides) {
    uint32_t cap = (uint32_t)(2 * (o->ncells + a.ndivides));
    double *r = realloc(s->retry_at, (size_t)cap * sizeof *r);
    if (!r) st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
    else {
      for (uint32_t c = s->retry_cap; c < cap; c++) r[c] = -INFINITY;
      s->retry_at = r, s->retry_cap = cap;
    }
  }
  for (size_t i = 0; st == SESSILE_OK && i < a.ndivides; i++) {
    if (s->time < s->retry_at[a.divides[i].cell]) continue;
    double d[3] = {a.divides[i].dir[0], a.divides[i].dir[1], a.divides[i].dir[2]};
    if (d[0] == 0 && d[1] == 0 && d[2] == 0) {
      /* the gradient vanished: a seeded random direction */
      double z = sessile_rng_range(&s->rng, -1, 1), phi = sessile_rng_range(&s->rng, 0, 2 * PI), q = sqrt(1 - z * z);
      d[0] = q * cos(phi), d[1] = q * sin(phi), d[2] = z;
    }
    st = divide(s, (uint32_t)a.divides[i].cell, d);
    if (st != SESSILE_OK)
      st = sessile_error_set(st, "sds: cell %d cannot divide at t = %g: %s", a.divides[i].cell, s->time,
                             sessile_error_message());
  }
  sessile_sds_actions_free(&a);
  SESSILE_CALL(st);
  return refresh(s);
}

/* --- frames ------------------------------------------------------------------ */
static sessile_status write_frame(sim *s, sessile_run *run, int frame, const char *ply_rel) {
  sessile_sds *o = &s->o;
  char rel[64], path[4096];
  /* the surface: boundary faces over all cells (unused cells are dropped by
   * remapping to the boundary's own vertices) */
  uint32_t *map = malloc(((size_t)o->ncells + 1) * sizeof *map);
  SESSILE_CHECK(map, SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
  uint32_t nv = 0;
  for (uint32_t c = 0; c < o->ncells; c++) map[c] = o->surface[c] ? nv++ : UINT32_MAX;
  int nf = 2 + (int)o->nmorph + (int)o->nstate;
  double *pos = malloc(((size_t)nv * 3 + 1) * sizeof *pos), *fields = malloc(((size_t)nv * nf + 1) * sizeof *fields);
  uint32_t *tri = malloc(((size_t)o->nfaces * 3 + 1) * sizeof *tri);
  const char **names = calloc((size_t)nf, sizeof *names);
  const double **fp = calloc((size_t)nf, sizeof *fp);
  sessile_status st = pos && fields && tri && names && fp ? SESSILE_OK
                                                       : sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
  if (st == SESSILE_OK) {
    for (uint32_t c = 0; c < o->ncells; c++) {
      if (map[c] == UINT32_MAX) continue;
      uint32_t v = map[c];
      memcpy(pos + 3 * (size_t)v, o->x + 3 * (size_t)c, 3 * sizeof *pos);
      fields[0 * (size_t)nv + v] = o->r[c];
      fields[1 * (size_t)nv + v] = c;
      for (uint32_t k = 0; k < o->nmorph; k++) fields[(2 + k) * (size_t)nv + v] = o->phi[(size_t)c * o->nmorph + k];
      for (uint32_t k = 0; k < o->nstate; k++)
        fields[(2 + o->nmorph + k) * (size_t)nv + v] = o->state[(size_t)c * o->nstate + k];
    }
    for (uint32_t f = 0; f < 3 * o->nfaces; f++) tri[f] = map[o->face[f]];
    names[0] = "radius", names[1] = "cell";
    for (uint32_t k = 0; k < o->nmorph; k++) names[2 + k] = sessile_sds_model_morph_name(s->model, (int)k);
    for (uint32_t k = 0; k < o->nstate; k++) names[2 + o->nmorph + k] = sessile_sds_model_state_name(s->model, (int)k);
    for (int k = 0; k < nf; k++) fp[k] = fields + (size_t)k * nv;
    sessile_mesh_part part = {"surface", pos, nv, tri, o->nfaces, NULL, fp};
    st = sessile_run_file(run, ply_rel, path, sizeof path);
    if (st == SESSILE_OK) st = sessile_write_ply_parts(path, 1, &part, nf, names);
  }
  if (st == SESSILE_OK && frame >= 0) {
    /* the complex: every cell with its fields, tets with their volumes */
    sessile_vtu_field pf[3 + SESSILE_SDS_MAX_VALUES * 2];
    int npf = 0;
    memset(pf, 0, sizeof pf);
    pf[npf].name = "radius", pf[npf].f64 = o->r, pf[npf++].components = 1;
    pf[npf].name = "velocity", pf[npf].f64 = o->v, pf[npf++].components = 3;
    pf[npf].name = "surface", pf[npf].u8 = o->surface, pf[npf++].components = 1;
    double *cf = malloc(((size_t)o->ncells * (o->nmorph + o->nstate) + (size_t)o->ntets + 1) * sizeof *cf);
    if (!cf) st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
    for (uint32_t k = 0; st == SESSILE_OK && k < o->nmorph + o->nstate && npf < (int)(sizeof pf / sizeof pf[0]); k++) {
      double *col = cf + (size_t)k * o->ncells;
      for (uint32_t c = 0; c < o->ncells; c++)
        col[c] = k < o->nmorph ? o->phi[(size_t)c * o->nmorph + k] : o->state[(size_t)c * o->nstate + (k - o->nmorph)];
      pf[npf].name = k < o->nmorph ? sessile_sds_model_morph_name(s->model, (int)k)
                                   : sessile_sds_model_state_name(s->model, (int)(k - o->nmorph));
      pf[npf].f64 = col, pf[npf++].components = 1;
    }
    if (st == SESSILE_OK) {
      double *vol = cf + (size_t)o->ncells * (o->nmorph + o->nstate);
      for (uint32_t t = 0; t < o->ntets; t++) vol[t] = sessile_sds_tet_volume(o, t);
      sessile_vtu_field tf = {.name = "volume", .f64 = vol, .components = 1};
      snprintf(rel, sizeof rel, "sds/frame_%04d.vtu", frame);
      st = sessile_run_file(run, rel, path, sizeof path);
      if (st == SESSILE_OK) st = sessile_write_vtu_tets(path, o->x, o->ncells, o->tet, o->ntets, npf, pf, 1, &tf);
    }
    free(cf);
  }
  free(map), free(pos), free(fields), free(tri), free(names), free(fp);
  return st;
}

static sessile_status write_pvd(sessile_run *run, int nframes) {
  char path[4096];
  int *steps = malloc(((size_t)nframes + 1) * sizeof *steps);
  char **files = calloc((size_t)nframes + 1, sizeof *files);
  sessile_status st = steps && files ? SESSILE_OK : sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
  for (int i = 0; st == SESSILE_OK && i < nframes; i++) {
    steps[i] = i;
    files[i] = malloc(32);
    if (!files[i]) st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
    else snprintf(files[i], 32, "frame_%04d.vtu", i);
  }
  if (st == SESSILE_OK) st = sessile_run_file(run, "sds/series.pvd", path, sizeof path);
  if (st == SESSILE_OK) st = sessile_write_pvd(path, nframes, steps, (const char *const *)files);
  for (int i = 0; files && i < nframes; i++) free(files[i]);
  free(files), free(steps);
  return st;
}

/* --- set-up ------------------------------------------------------------------ */
/* Tips: the surface cell farthest along each tip direction from the
 * centroid (ties to the lower index) gets tip = 1, and the attraction point
 * pulls the tips. */
static sessile_status mark_tips(sim *s, const char *where) {
  sessile_sds *o = &s->o;
  int nt = sessile_sds_model_ntips(s->model);
  if (nt == 0) return SESSILE_OK;
  SESSILE_CHECK(s->tip_state >= 0, SESSILE_ERR_USAGE, "%s: the model names tips but has no 'state tip'", where);
  double cen[3] = {0, 0, 0};
  for (uint32_t c = 0; c < o->ncells; c++)
    for (int k = 0; k < 3; k++) cen[k] += o->x[3 * (size_t)c + k] / o->ncells;
  for (int i = 0; i < nt; i++) {
    const double *d = sessile_sds_model_tip(s->model, i);
    double best = -INFINITY;
    uint32_t bc = UINT32_MAX;
    for (uint32_t c = 0; c < o->ncells; c++) {
      if (!o->surface[c]) continue;
      double q[3], l = 0, dot = 0;
      for (int k = 0; k < 3; k++) q[k] = o->x[3 * (size_t)c + k] - cen[k], l += q[k] * q[k];
      l = sqrt(l);
      for (int k = 0; k < 3; k++) dot += q[k] * d[k];
      if (l > 0 && dot / l > best) best = dot / l, bc = c;
    }
    SESSILE_CHECK(bc != UINT32_MAX, SESSILE_ERR_USAGE, "%s: no surface cell for tip %d", where, i + 1);
    o->state[(size_t)bc * o->nstate + (uint32_t)s->tip_state] = 1;
    if (s->p.nattract) o->attract[bc] = 0;
  }
  return SESSILE_OK;
}

/* §3.6 automated: a tip with no interior cell below it gets one by dividing
 * the cell the check names, inward. */
static sessile_status cells_below_tips(sim *s) {
  sessile_sds *o = &s->o;
  sessile_morph_cells cells = cells_of(s);
  sessile_sds_tip_check *chk = NULL;
  int n = 0;
  SESSILE_CALL(sessile_sds_tips_below(&cells, o->surface, NULL, o->state, (int)o->nstate, s->tip_state, 0.7, &chk, &n));
  sessile_status st = SESSILE_OK;
  for (int i = 0; i < n && st == SESSILE_OK; i++) {
    if (chk[i].below >= 0) continue;
    st = divide(s, (uint32_t)chk[i].split, chk[i].inward);
    if (st == SESSILE_OK) {
      /* the daughter that went inside is not a tip */
      uint32_t b = s->o.ncells - 1;
      s->o.state[(size_t)b * s->o.nstate + (uint32_t)s->tip_state] = 0;
      s->o.attract[b] = -1;
      st = neighbours(s);
    }
  }
  free(chk);
  s->st->divisions = 0, s->div_interval = 0; /* set-up, not growth */
  return st;
}

/* Everything about the model that needs no device: the text, the physics
 * keys, the starting sphere, the run's length. */
static sessile_status check_model(sim *s, const char *where, const sessile_sds_run_params *params, int *level,
                                  double *radius) {
  SESSILE_CALL(sessile_sds_model_parse(s->text, where, &s->model));
  if (params) {
    s->prm = *params;
    SESSILE_CALL(sessile_params_check(&sessile_sds_run_param_table, &s->prm));
  } else
    SESSILE_CALL(sessile_sds_run_params_of_model(s->text, where, &s->prm));
  SESSILE_CALL(read_physics(s, where));
  *level = s->prm.sphere_subdivisions + 1;
  *radius = s->prm.sphere_radius;
  double t_end = param1(s->model, "t_end", 100), frames = param1(s->model, "frames", 20);
  SESSILE_CHECK(t_end >= 0 && t_end <= 1e9 && frames >= 1 && frames <= 100000 && frames == floor(frames),
                SESSILE_ERR_USAGE, "%s: t_end must be in [0, 1e9] and frames an integer in 1..100000", where);
  return SESSILE_OK;
}

/* A realisation of the starting sphere (the model's start_jitter J, docs/
 * sds_rules.md): each vertex moved along its radius by J x the mean edge
 * length x a normal deviate clipped to +-3, drawn from the seed's own stream
 * (2; the division directions draw from 1).  The sphere stays star-shaped
 * about its centre for J <= 0.2, so TetGen meshes it. */
static void jitter_sphere(sessile_surface *srf, double jitter, uint64_t seed) {
  double len = 0, c[3] = {0, 0, 0};
  for (uint32_t f = 0; f < srf->nf; f++)
    for (int k = 0; k < 3; k++) {
      const double *a = srf->pos + 3 * (size_t)srf->tri[3 * (size_t)f + k];
      const double *b = srf->pos + 3 * (size_t)srf->tri[3 * (size_t)f + (k + 1) % 3];
      len += sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
    }
  len /= srf->nf ? 3.0 * srf->nf : 1.0;
  for (uint32_t v = 0; v < srf->nv; v++)
    for (int k = 0; k < 3; k++) c[k] += srf->pos[3 * (size_t)v + k] / srf->nv;
  uint64_t rng = sessile_rng_stream(seed, 2);
  for (uint32_t v = 0; v < srf->nv; v++) {
    double *x = srf->pos + 3 * (size_t)v, d[3], n = 0;
    for (int k = 0; k < 3; k++) d[k] = x[k] - c[k], n += d[k] * d[k];
    n = sqrt(n);
    double z = fmax(-3.0, fmin(3.0, sessile_rng_normal(&rng)));
    if (n > 0)
      for (int k = 0; k < 3; k++) x[k] += jitter * len * z * d[k] / n;
  }
}

/* The starting organism: the model's `surface = "FILE.ply"` (relative to
 * the model file's folder), or the icosphere (sphere_radius,
 * sphere_subdivisions), through TetGen.  A surface that is not closed and
 * consistently oriented, or that TetGen rejects, is a usage error. */
static sessile_status import_organism(sim *s, const char *where, int level, double radius) {
  uint32_t nm = (uint32_t)sessile_sds_model_nmorph(s->model), ns = (uint32_t)sessile_sds_model_nstate(s->model);
  const sessile_sds_param *sf = sessile_sds_model_param_find(s->model, "surface");
  double jitter = s->prm.start_jitter;
  SESSILE_CHECK(!(sf && jitter > 0), SESSILE_ERR_USAGE,
                "%s: start_jitter moves the icosphere's vertices; a model with its own surface has none to move", where);
  if (!sf) {
    const double c0[3] = {0, 0, 0};
    if (jitter == 0) return sessile_sds_from_icosphere(level, radius, c0, 0, nm, ns, s->density, &s->o);
    sessile_surface srf = {0};
    SESSILE_CALL(sessile_surface_icosphere(level, radius, c0, &srf));
    jitter_sphere(&srf, jitter, s->seed);
    sessile_status st = sessile_sds_from_surface(&srf, NULL, 0, nm, ns, s->density, &s->o);
    sessile_surface_free(&srf);
    return st;
  }
  SESSILE_CHECK(sf->nvalues == 0 && sf->text[0], SESSILE_ERR_USAGE, "%s:%d: surface names a PLY file: surface = \"FILE.ply\"",
                where, sf->line);
  char path[4096];
  const char *slash = strrchr(where, '/');
  if (sf->text[0] == '/' || !slash) snprintf(path, sizeof path, "%s", sf->text);
  else snprintf(path, sizeof path, "%.*s/%s", (int)(slash - where), where, sf->text);
  sessile_surface srf;
  SESSILE_CALL(sds_read_surface_ply(path, &srf));
  /* closed and consistently oriented (any genus: the check's Euler number is
   * the surface's own, V - 3F/2 + F) */
  sessile_status st = sessile_surface_check(&srf, (int)srf.nv - (int)(srf.nf / 2), 0);
  if (st != SESSILE_OK)
    st = sessile_error_set(SESSILE_ERR_USAGE, "%s:%d: surface '%s' is not a closed, consistently oriented surface: %s",
                           where, sf->line, path, sessile_error_message());
  if (st == SESSILE_OK) {
    st = sessile_sds_from_surface(&srf, NULL, 0, nm, ns, s->density, &s->o);
    if (st == SESSILE_ERR_USAGE)
      st = sessile_error_set(st, "%s:%d: surface '%s': %s", where, sf->line, path, sessile_error_message());
  }
  sessile_surface_free(&srf);
  return st;
}

sessile_status sessile_sds_model_check(const char *text, const char *name, const sessile_sds_run_params *params,
                                       double t_end, uint64_t max_steps) {
  sim s;
  memset(&s, 0, sizeof s);
  s.text = text, s.seed = 1; /* the estimate: any realisation of the start will do */
  int level;
  double radius;
  const char *where = name ? name : "model";
  sessile_status st = check_model(&s, where, params, &level, &radius);
  if (st == SESSILE_OK) {
    /* the work it would take: steps at the integrator's stable step of the
     * starting organism (growth and division only make steps smaller) */
    st = import_organism(&s, where, level, radius);
    if (st == SESSILE_OK) {
      if (t_end < 0) t_end = param1(s.model, "t_end", 100);
      double dt = fmin(s.p.stable_safety * sessile_sds_stable_dt(&s.o, &s.p), s.p.dt_max);
      double steps = dt > 0 ? t_end / dt : INFINITY;
      if (!(steps <= (double)max_steps))
        st = sessile_error_set(SESSILE_ERR_USAGE,
                               "%s: reaching t = %g needs at least %.3g steps (stable step %.3g at the start), more "
                               "than --max-steps %llu: soften the springs or shorten the run",
                               where, t_end, steps, dt, (unsigned long long)max_steps);
    }
  }
  sessile_sds_model_destroy(s.model);
  sessile_surface_free(&s.rock);
  sessile_sds_free(&s.o);
  return st;
}

/* The starting organism's centroid and size (its largest distance from the
 * centroid): the blow-up test's yardstick. */
static void measure_start(sim *s) {
  const sessile_sds *o = &s->o;
  for (int k = 0; k < 3; k++) s->c0[k] = 0;
  for (uint32_t c = 0; c < o->ncells; c++)
    for (int k = 0; k < 3; k++) s->c0[k] += o->x[3 * (size_t)c + k] / o->ncells;
  s->size0 = 0;
  for (uint32_t c = 0; c < o->ncells; c++) {
    double d2 = 0;
    for (int k = 0; k < 3; k++) d2 += (o->x[3 * (size_t)c + k] - s->c0[k]) * (o->x[3 * (size_t)c + k] - s->c0[k]);
    s->size0 = fmax(s->size0, sqrt(d2));
  }
}

/* --- the per-step log: sds/steps.csv (the paper's Figure 12 per step) --- */
#define STEPLOG "sds/steps.csv"
#define STEPLOG_FLUSH ((size_t)1 << 20) /* bytes of rows kept between appends at most */
static const char STEPLOG_HEADER[] = "step,time,dt,cells,tets,ms,divisions,inversions\n";

/* One row: the step just made, its wall time and its events. */
static sessile_status steplog_row(sim *s, double dt, double ms, uint64_t divisions, uint64_t inversions) {
  if (s->steplog_cap - s->steplog_len < 160) {
    size_t cap = s->steplog_cap ? 2 * s->steplog_cap : 1u << 16;
    char *b = realloc(s->steplog, cap);
    SESSILE_CHECK(b, SESSILE_ERR_NO_MEMORY, "sds: out of host memory for the step log");
    s->steplog = b, s->steplog_cap = cap;
  }
  int k = snprintf(s->steplog + s->steplog_len, s->steplog_cap - s->steplog_len,
                   "%llu,%.17g,%.17g,%u,%u,%.4f,%llu,%llu\n", (unsigned long long)s->st->steps, s->time, dt,
                   s->o.ncells, s->o.ntets, ms, (unsigned long long)divisions, (unsigned long long)inversions);
  SESSILE_CHECK(k > 0 && (size_t)k < s->steplog_cap - s->steplog_len, SESSILE_ERR_INTERNAL, "sds: step log row too long");
  s->steplog_len += (size_t)k;
  return SESSILE_OK;
}

/* Appends the rows kept so far: before every checkpoint (the checkpoint keeps
 * the log's length), when a MiB has gathered between frames (a long frame
 * interval must not hold millions of rows; a resume cuts what lies past the
 * checkpoint), and at the end of the run, whatever its end. */
static sessile_status steplog_flush(sim *s, sessile_run *run) {
  if (!s->steplog_len) return SESSILE_OK;
  sessile_status st = sessile_run_log(run, STEPLOG, s->steplog, s->steplog_len);
  s->steplog_len = 0;
  return st;
}

/* The loop's scalars to and from the checkpoint (sds_checkpoint.h). */
static sessile_status save(sim *s, sessile_run *run) {
  SESSILE_CALL(steplog_flush(s, run));
  const sessile_sds_run_stats *t = s->st;
  sds_ckpt_loop l = {.version = SDS_CKPT_VERSION, .key = s->key, .time = s->time, .dt = s->dt,
                     .stalled = s->stalled, .rng = s->rng, .frame = s->frame,
                     .steps_frame = s->steps_frame, .div_interval = s->div_interval,
                     .inv_interval = s->inv_interval, .steps = t->steps, .divisions = t->divisions,
                     .inversions = t->inversions, .resisted = t->resisted, .slivers = t->slivers,
                     .deferred = t->deferred, .repairs = t->repairs, .c0 = {s->c0[0], s->c0[1], s->c0[2]}, .size0 = s->size0,
                     .retry_cap = s->retry_at ? s->retry_cap : 0, .nsliver = s->nsliver};
  return sds_ckpt_write(run, s->frame, &s->o, &l, s->retry_at, s->sliver);
}

static sessile_status restore(sim *s, const sessile_ckpt *ck) {
  sds_ckpt_loop l;
  SESSILE_CALL(sds_ckpt_read(ck, s->key, (uint32_t)sessile_sds_model_nmorph(s->model),
                             (uint32_t)sessile_sds_model_nstate(s->model), &s->o, &l, &s->retry_at, &s->sliver));
  sessile_sds_run_stats *t = s->st;
  s->time = l.time, s->dt = l.dt, s->stalled = (int)l.stalled, s->rng = l.rng;
  s->frame = (int)l.frame, s->steps_frame = l.steps_frame;
  s->div_interval = l.div_interval, s->inv_interval = l.inv_interval;
  t->steps = l.steps, t->divisions = l.divisions, t->inversions = l.inversions, t->resisted = l.resisted;
  t->slivers = l.slivers, t->deferred = l.deferred, t->repairs = l.repairs, t->frames = s->frame;
  memcpy(s->c0, l.c0, sizeof s->c0);
  s->size0 = l.size0, s->retry_cap = (uint32_t)l.retry_cap;
  s->nsliver = s->sliver_cap = (uint32_t)l.nsliver;
  if (!s->retry_cap) free(s->retry_at), s->retry_at = NULL;
  SESSILE_CHECK(s->frame >= 1 && s->frame <= s->frames + 1 && isfinite(s->time) && s->dt > 0 && s->size0 > 0,
                SESSILE_ERR_IO, "the checkpoint's loop section does not fit this run (damaged?)");
  s->resumed = 1;
  return SESSILE_OK;
}

static sessile_status setup(sim *s, const sessile_sds_run_options *opt) {
  const char *where = opt->model_name ? opt->model_name : "model";
  int level;
  double radius;
  s->text = opt->model_text;
  SESSILE_CALL(check_model(s, where, opt->params, &level, &radius));
  s->t_end = opt->t_end >= 0 ? opt->t_end : param1(s->model, "t_end", 100);
  s->frames = opt->frames >= 0 ? opt->frames : (int)param1(s->model, "frames", 20);
  SESSILE_CHECK(s->t_end >= 0 && isfinite(s->t_end) && s->frames >= 1 && s->frames <= 100000, SESSILE_ERR_USAGE,
                "sds: t_end must be >= 0 and frames in 1..100000");
  s->key = sds_ckpt_key(s->text, opt->seed, s->t_end, s->frames, opt->max_cells);
  if (opt->params) { /* values apart from the model's own (--set, --config) belong to the key */
    sessile_sds_run_params own;
    SESSILE_CALL(sessile_sds_run_params_of_model(s->text, where, &own));
    s->key = sds_ckpt_key_params(s->key, &own, &s->prm);
  }
  cJSON *man = sessile_run_manifest(opt->run);
  cJSON_DeleteItemFromObjectCaseSensitive(man, "parameters");
  cJSON_AddItemToObject(man, "parameters", sessile_params_to_json(&sessile_sds_run_param_table, &s->prm));
  int nm = sessile_sds_model_nmorph(s->model), ns = sessile_sds_model_nstate(s->model);
  s->tip_state = sessile_sds_model_state_index(s->model, "tip");
  s->birth_state = sessile_sds_model_state_index(s->model, "birth_radius");
  const sessile_ckpt *ck = sessile_run_checkpoint_loaded(opt->run);
  if (ck) {
    SESSILE_CALL(restore(s, ck));
    SESSILE_CALL(neighbours(s));
  } else {
    SESSILE_CALL(import_organism(s, where, level, radius));
    for (uint32_t c = 0; c < s->o.ncells; c++) {
      for (int k = 0; k < nm; k++) s->o.phi[(size_t)c * nm + k] = sessile_sds_model_morph_start(s->model, k);
      for (int k = 0; k < ns; k++) s->o.state[(size_t)c * ns + k] = sessile_sds_model_state_start(s->model, k);
    }
    if (s->birth_state >= 0)
      for (uint32_t c = 0; c < s->o.ncells; c++) s->o.state[(size_t)c * ns + (uint32_t)s->birth_state] = s->o.r[c];
    SESSILE_CALL(mark_tips(s, where));
    SESSILE_CALL(neighbours(s));
    if (s->prm.tips_below && s->tip_state >= 0) SESSILE_CALL(cells_below_tips(s));
    measure_start(s);
    s->dt = s->p.dt;
  }
  SESSILE_CALL(sessile_sds_gpu_create(opt->gpu, &s->o, &s->p, &s->pg));
  SESSILE_CALL(sessile_morph_gpu_create(opt->gpu, &s->mg));
  return SESSILE_OK;
}

static void teardown(sim *s) {
  sessile_sds_model_destroy(s->model);
  sessile_sds_gpu_destroy(s->pg);
  sessile_morph_gpu_destroy(s->mg);
  sessile_sds_free(&s->o);
  sessile_surface_free(&s->rock);
  free(s->nbr_off), free(s->nbr), free(s->xprev), free(s->retry_at), free(s->sliver), free(s->steplog);
}

static sessile_status record(sim *s, sessile_run *run, int frame, double ms_per_step, uint64_t steps) {
  cJSON *r = cJSON_CreateObject();
  SESSILE_CHECK(r, SESSILE_ERR_NO_MEMORY, "out of host memory");
  cJSON_AddNumberToObject(r, "frame", frame);
  cJSON_AddNumberToObject(r, "time", s->time);
  cJSON_AddNumberToObject(r, "cells", s->o.ncells);
  cJSON_AddNumberToObject(r, "tets", s->o.ntets);
  cJSON_AddNumberToObject(r, "steps", (double)steps);
  cJSON_AddNumberToObject(r, "ms_per_step", ms_per_step);
  cJSON_AddNumberToObject(r, "dt", s->dt);
  cJSON_AddNumberToObject(r, "divisions", (double)s->div_interval);
  cJSON_AddNumberToObject(r, "inversions", (double)s->inv_interval);
  s->div_interval = s->inv_interval = 0;
  sessile_status st = sessile_run_record(run, r);
  cJSON_Delete(r);
  return st;
}

/* --- the loop --------------------------------------------------------------- */
/* A blow-up (docs/sds.md, "Blow-ups"): the step from t = s->time (step
 * steps + 1) left no usable state.  Nothing of the step is written; the
 * message says what happened, when, and what to try. */
static sessile_status blowup(sim *s, const char *fmt, ...) {
  sessile_sds_run_stats *t = s->st;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(t->blowup_cause, sizeof t->blowup_cause, fmt, ap);
  va_end(ap);
  t->blowup = 1, t->blowup_time = s->step_t0, t->blowup_step = t->steps + 1;
  return sessile_error_set(SESSILE_ERR_NUMERIC,
                           "sds: blow-up in step %llu from t = %.9g: %s; the last good frame is frame_%04d; try "
                           "weaker forces (gravity, attractor), more damping, stiffer volume springs "
                           "(volume_stiffness) or slower growth",
                           (unsigned long long)t->blowup_step, s->step_t0, t->blowup_cause, s->frame - 1);
}

/* The state after the physics: every position and velocity finite, every
 * cell within 1e6 starting sizes of the starting centroid. */
static sessile_status check_motion(sim *s) {
  const sessile_sds *o = &s->o;
  double far2 = 1e12 * s->size0 * s->size0;
  for (uint32_t c = 0; c < o->ncells; c++) {
    const double *x = o->x + 3 * (size_t)c, *v = o->v + 3 * (size_t)c;
    if (!isfinite(x[0] + x[1] + x[2]) || !isfinite(v[0] + v[1] + v[2]))
      return blowup(s, "cell %u's position or velocity is not finite", c);
    double d2 = 0;
    for (int k = 0; k < 3; k++) d2 += (x[k] - s->c0[k]) * (x[k] - s->c0[k]);
    if (d2 > far2)
      return blowup(s, "cell %u is %.3g u from the start's centre, more than 1e6 times the starting size %.3g u", c,
                    sqrt(d2), s->size0);
  }
  return SESSILE_OK;
}

/* The state after the rules: radii positive and finite, morphogens and
 * state variables finite (a runaway growth or production). */
static sessile_status check_cells(sim *s) {
  const sessile_sds *o = &s->o;
  for (uint32_t c = 0; c < o->ncells; c++) {
    if (!(o->r[c] > 0 && isfinite(o->r[c]) && isfinite(o->m[c])))
      return blowup(s, "cell %u's radius %g or mass %g is not positive and finite (a runaway growth rule?)", c,
                    o->r[c], o->m[c]);
    for (uint32_t k = 0; k < o->nmorph; k++)
      if (!isfinite(o->phi[(size_t)c * o->nmorph + k]))
        return blowup(s, "cell %u's morphogen %s is not finite", c, sessile_sds_model_morph_name(s->model, (int)k));
    for (uint32_t k = 0; k < o->nstate; k++)
      if (!isfinite(o->state[(size_t)c * o->nstate + k]))
        return blowup(s, "cell %u's state %s is not finite", c, sessile_sds_model_state_name(s->model, (int)k));
  }
  return SESSILE_OK;
}

/* One step (docs/sds.md, "The loop"). */
static sessile_status step(sim *s, double next_frame) {
  free(s->xprev);
  s->xprev = malloc((size_t)s->o.ncells * 3 * sizeof *s->xprev);
  SESSILE_CHECK(s->xprev, SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
  memcpy(s->xprev, s->o.x, (size_t)s->o.ncells * 3 * sizeof *s->xprev);
  double dt = s->dt, elapsed = 0;
  s->step_t0 = s->time;
  int clamped = s->time + dt > next_frame;
  if (clamped) dt = fmax(next_frame - s->time, 1e-12);
  double try_dt = dt;
  sessile_status st = sessile_sds_gpu_advance(s->pg, 1, &try_dt, &elapsed);
  if (st == SESSILE_ERR_NUMERIC) {
    /* a non-finite state or a step below dt_min: the integrator's verdict */
    char why[512];
    const char *m = sessile_error_message();
    snprintf(why, sizeof why, "%s", strncmp(m, "sds: ", 5) ? m : m + 5);
    return blowup(s, "%s", why);
  }
  SESSILE_CALL(st);
  /* step control across calls (one step per call, so that an inversion is
   * rewound over one step): the integrator proposes the next step; a step cut
   * short to land on a frame keeps the step it had, unless it was undone */
  if (!clamped || elapsed < dt * (1 - 1e-12)) s->dt = try_dt;
  SESSILE_CALL(sessile_sds_gpu_download(s->pg, &s->o));
  SESSILE_CALL(check_motion(s));
  int handled = 0;
  double frac = 1;
  SESSILE_CALL(inversions(s, &handled, &frac));
  if (handled) {
    /* rewound to the inversion: the elapsed time shrinks with it */
    elapsed *= frac;
    SESSILE_CALL(refresh(s));
  }
  if (elapsed > 0) {
    s->time += elapsed;
    SESSILE_CALL(rules(s, elapsed));
    SESSILE_CALL(check_cells(s));
    s->stalled = 0;
  } else if (++s->stalled >= 1000)
    return blowup(s, "time stands still: tets keep inverting at the start of the step for 1000 steps");
  s->st->steps++, s->steps_frame++;
  return SESSILE_OK;
}

static sessile_status loop(sim *s, const sessile_sds_run_options *opt) {
  double frame_dt = s->t_end / s->frames;
  if (!s->resumed) {
    SESSILE_CALL(sessile_run_log(opt->run, STEPLOG, STEPLOG_HEADER, sizeof STEPLOG_HEADER - 1));
    SESSILE_CALL(write_frame(s, opt->run, 0, "sds/frame_0000.ply"));
    SESSILE_CALL(record(s, opt->run, 0, 0, 0));
    s->st->frames = s->frame = 1;
    SESSILE_CALL(write_pvd(opt->run, 1));
    SESSILE_CALL(save(s, opt->run));
  }
  double tf = sessile_wall_seconds();
  while (s->time < s->t_end * (1 - 1e-12)) {
    SESSILE_CHECK(s->o.ncells <= opt->max_cells, SESSILE_ERR_NO_MEMORY,
                  "sds: %u cells at t = %g, more than the limit %u (--max-cells)", s->o.ncells, s->time, opt->max_cells);
    double next_frame = s->frame * frame_dt;
    double t0 = s->time, w0 = sessile_wall_seconds();
    uint64_t d0 = s->st->divisions, i0 = s->st->inversions;
    SESSILE_CALL(step(s, next_frame));
    SESSILE_CALL(steplog_row(s, s->time - t0, 1e3 * (sessile_wall_seconds() - w0), s->st->divisions - d0,
                             s->st->inversions - i0));
    if (s->steplog_len >= STEPLOG_FLUSH) SESSILE_CALL(steplog_flush(s, opt->run));
    int saved = 0;
    if (s->time >= next_frame * (1 - 1e-12)) {
      double now = sessile_wall_seconds();
      char rel[64];
      snprintf(rel, sizeof rel, "sds/frame_%04d.ply", s->frame);
      SESSILE_CALL(write_frame(s, opt->run, s->frame, rel));
      uint64_t n = s->steps_frame;
      SESSILE_CALL(record(s, opt->run, s->frame, 1e3 * (now - tf) / (double)(n ? n : 1), n));
      s->st->frames = ++s->frame;
      tf = now, s->steps_frame = 0;
      SESSILE_CALL(write_pvd(opt->run, s->frame));
      SESSILE_CALL(save(s, opt->run));
      saved = 1;
    }
    int stop = sessile_run_stop_requested(opt->run);
    if (stop) {
      /* the state after any step resumes exactly (the device holds nothing
       * the host has not: every step ends with an upload) */
      if (!saved) SESSILE_CALL(save(s, opt->run));
      return sessile_error_set(SESSILE_ERR_INTERRUPTED, "stopped by signal %d at t = %g", stop, s->time);
    }
  }
  SESSILE_CALL(write_pvd(opt->run, s->frame));
  SESSILE_CALL(steplog_flush(s, opt->run));
  return write_frame(s, opt->run, -1, "sds/final.ply");
}

sessile_status sessile_sds_run(const sessile_sds_run_options *opt, sessile_sds_run_stats *st) {
  memset(st, 0, sizeof *st);
  SESSILE_CHECK(opt->run && opt->gpu && opt->model_text, SESSILE_ERR_USAGE, "sessile sds run needs a run, a device and a model");
  sim s;
  memset(&s, 0, sizeof s);
  s.st = st;
  s.rng = sessile_rng_stream(opt->seed, 1);
  s.seed = opt->seed;
  double t0 = sessile_wall_seconds();
  sessile_status r = setup(&s, opt);
  if (r == SESSILE_OK) r = loop(&s, opt);
  if (r != SESSILE_OK) { /* the steps up to a failure stay in the log, and the failure's message stays */
    char why[1024];
    snprintf(why, sizeof why, "%s", sessile_error_message());
    if (steplog_flush(&s, opt->run) != SESSILE_OK) sessile_error_set(r, "%s (and then: %s)", why, sessile_error_message());
    else sessile_error_set(r, "%s", why);
  }
  st->wall_s = sessile_wall_seconds() - t0;
  st->time = s.time, st->cells = s.o.ncells, st->tets = s.o.ntets;
  st->resumed = s.resumed;
  teardown(&s);
  return r;
}
