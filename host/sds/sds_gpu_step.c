/* The SDS physics steps on the GPU: per-element forces, the per-cell
 * gather and integrator step, the stable-step bound and the step control
 * (docs/sds.md "Integrator"), the inverted-tet flags, and the benchmark's
 * timings of the contacts. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sds/sds_gpu_internal.h"
#include "sds/sds_gpu_rules.h"

static sessile_status record_edge(sessile_sds_gpu *s, int c, const sds_push *p) {
  if (!s->nedges) return SESSILE_OK;
  sessile_buffer *b[] = {s->b[B_SP], s->b[B_X0 + c], s->b[B_RM], s->b[B_TOPO], s->b[B_SM], s->b[B_ELF], s->b[B_EVENT]};
  return sessile_cmd_dispatch(s->cmd, sds_gpu_kern(s, SDS_EDGE), sds_gpu_groups(s, SDS_EDGE, s->nedges), b, p);
}

/* Both in one dispatch (elem_force: the edges, then the tets). */
static sessile_status record_elem(sessile_sds_gpu *s, int c, const sds_push *p) {
  sessile_buffer *b[] = {s->b[B_SP], s->b[B_X0 + c], s->b[B_V0 + c], s->b[B_RM], s->b[B_TOPO], s->b[B_SM],
                         s->b[B_ELF], s->b[B_EVENT], s->b[B_FLAG]};
  return sessile_cmd_dispatch(s->cmd, sds_gpu_kern(s, SDS_ELEM), sds_gpu_elem_groups(s), b, p);
}

static sessile_status record_tet(sessile_sds_gpu *s, int c, const sds_push *p) {
  if (!s->ntets) return SESSILE_OK;
  sessile_buffer *b[] = {s->b[B_SP], s->b[B_X0 + c], s->b[B_V0 + c], s->b[B_RM], s->b[B_TOPO], s->b[B_SM],
                         s->b[B_ELF], s->b[B_EVENT], s->b[B_FLAG]};
  return sessile_cmd_dispatch(s->cmd, sds_gpu_kern(s, SDS_TET), sds_gpu_groups(s, SDS_TET, s->ntets), b, p);
}

/* Records stable_min: the min of the bound (and in a batch the check of
 * the step before, kernels.def). */
sessile_status sds_gpu_record_stable_min(sessile_sds_gpu *s, const sds_push *p, int c) {
  sessile_buffer *rev = s->rules ? sds_gpu_rules_buffer(s->rules, SDS_RULES_EVENT) : s->b[B_EVENT];
  sessile_buffer *bm[] = {s->b[B_SP],   s->b[B_STAB],   s->b[B_STEP],       s->b[B_EVENT], s->b[B_MOVE],
                          s->b[B_TOPO], s->b[B_RM],     s->b[B_RB],         rev,           s->b[B_DISP],
                          s->b[B_SLIVER], s->b[B_X0 + 1 - c], s->b[B_X0 + c]};
  return sessile_cmd_dispatch(s->cmd, s->k[SDS_STABLE_MIN], 1, bm, p);
}

uint32_t sds_gpu_elem_groups(const sessile_sds_gpu *s) {
  return sds_gpu_groups(s, SDS_ELEM, s->nedges > s->ntets ? s->nedges : s->ntets);
}

int sds_gpu_stable_all(const sessile_sds_gpu *s) {
  return sds_gpu_kern(s, SDS_STABLE) == s->k[SDS_STABLE_TEX] && sds_gpu_fused_tail(s, s->ncells, SDS_FUSE_MIN_CELLS);
}

uint32_t sds_gpu_stable_groups(const sessile_sds_gpu *s) {
  if (!sds_gpu_stable_all(s)) return sds_gpu_groups(s, SDS_STABLE, s->ncells);
  return sds_gpu_tail_groups(sessile_kernel_local_size(s->k[SDS_STABLE_ALL]), s->ncells, s->tail_cap);
}

/* Records the stable bound (after record_edge and record_tet in mode 2,
 * whose terms it reads): per cell, then the min and the capped step into
 * stab. */
static sessile_status record_stable(sessile_sds_gpu *s, const sds_push *p, int c) {
  if (sds_gpu_stable_all(s)) {
    sessile_buffer *rev = s->rules ? sds_gpu_rules_buffer(s->rules, SDS_RULES_EVENT) : s->b[B_EVENT];
    sessile_buffer *b[] = {s->b[B_SP],   s->b[B_RM],   s->b[B_TOPO], s->b[B_ELF], s->b[B_STAB],
                           s->b[B_EVENT], s->b[B_STEP], s->b[B_MOVE], s->b[B_TOPO], s->b[B_RM],
                           s->b[B_RB],   rev,          s->b[B_DISP], s->b[B_CNT],
                           s->b[B_SLIVER], s->b[B_X0 + 1 - c], s->b[B_X0 + c]};
    return sessile_cmd_dispatch(s->cmd, s->k[SDS_STABLE_ALL], sds_gpu_stable_groups(s), b, p);
  }
  sessile_buffer *b[] = {s->b[B_SP], s->b[B_RM], s->b[B_TOPO], s->b[B_ELF], s->b[B_STAB], s->b[B_EVENT]};
  SESSILE_CALL(sessile_cmd_dispatch(s->cmd, sds_gpu_kern(s, SDS_STABLE), sds_gpu_groups(s, SDS_STABLE, s->ncells), b, p));
  return sds_gpu_record_stable_min(s, p, c);
}

sessile_status sds_gpu_record_forces(sessile_sds_gpu *s, int c, double dt, int damping, int mode, uint32_t batch) {
  sds_push p = sds_gpu_push_of(s, dt, damping, mode);
  p.batch = batch;
  int nx = 1 - c;
  if (s->nedges && s->ntets && sds_gpu_fused(s, s->ntets, SDS_FUSE_ELEM_TETS)) {
    SESSILE_CALL(record_elem(s, c, &p));
  } else {
    SESSILE_CALL(record_edge(s, c, &p));
    SESSILE_CALL(record_tet(s, c, &p));
  }
  if (mode == 2) SESSILE_CALL(record_stable(s, &p, c));
  sessile_buffer *b[] = {s->b[B_SP],   s->b[B_X0 + c], s->b[B_V0 + c], s->b[B_RM],      s->b[B_ATTRACT],
                         s->b[B_TOPO], s->b[B_ELF],    s->b[B_WORLD],  s->b[B_OBSTRI],  s->b[B_LIST],
                         s->b[B_XB],   s->b[B_X0 + nx],
                         s->b[B_V0 + nx], s->b[B_F],   s->b[B_MOVE],    s->b[B_STAB]};
  return sessile_cmd_dispatch(s->cmd, sds_gpu_kern(s, SDS_GATHER), sds_gpu_groups(s, SDS_GATHER, s->ncells), b, &p);
}

sessile_status sds_gpu_record_inverted(sessile_sds_gpu *s, int c, uint32_t batch) {
  sds_push p = sds_gpu_push_of(s, 0.0, 0, 0);
  p.batch = batch;
  sessile_buffer *b[] = {s->b[B_X0 + c], s->b[B_TOPO], s->b[B_FLAG], s->b[B_EVENT], s->b[B_SLIVER]};
  return sessile_cmd_dispatch(s->cmd, sds_gpu_kern(s, SDS_INVERTED), sds_gpu_groups(s, SDS_INVERTED, s->ntets), b, &p);
}

/* One force evaluation (mode 0) or step (mode 1, or 2 with the step capped
 * by the stable bound) in one submission; a step also flags the inverted
 * tets of its result (read by sessile_sds_gpu_inverted without a submission
 * of its own). */
static sessile_status run_forces(sessile_sds_gpu *s, double dt, int damping, int mode) {
  SESSILE_CALL(sds_gpu_lists_ensure(s));
  SESSILE_CALL(sds_gpu_begin(s));
  SESSILE_CALL(sds_gpu_record_forces(s, s->cur, dt, damping, mode, 0));
  int nx = 1 - s->cur, rec = mode != 0 && !sessile_buffer_host_ptr(s->b[B_X0 + nx]);
  if (mode != 0 && s->ntets) SESSILE_CALL(sds_gpu_record_inverted(s, nx, 0));
  if (rec) { /* the loop downloads every step's x, v: in this submission */
    SESSILE_CALL(sessile_cmd_download_reals(s->cmd, s->b[B_X0 + nx], 0, s->hx, 3 * (size_t)s->ncells));
    SESSILE_CALL(sessile_cmd_download_reals(s->cmd, s->b[B_V0 + nx], 0, s->hv, 3 * (size_t)s->ncells));
  }
  SESSILE_CALL(sessile_cmd_end(s->cmd));
  s->flags_cur = -1, s->mirror = -1;
  SESSILE_CALL(sds_gpu_submit(s));
  if (mode != 0) s->flags_cur = nx;
  if (rec) s->mirror = nx;
  return SESSILE_OK;
}

sessile_status sessile_sds_gpu_steps(sessile_sds_gpu *s, uint32_t steps, double dt) {
  SESSILE_CHECK(steps >= 1 && steps <= 1024, SESSILE_ERR_USAGE, "sds: steps per batch must be 1..1024 (got %u)", steps);
  /* no move check inside a batch: the lists are built again before every
   * step (at the capacity of a build at the start), so that a batch gives
   * the bytes of single steps */
  SESSILE_CALL(sds_gpu_lists_ensure(s));
  int lists = sds_gpu_contacts_on(s);
  uint32_t *lmax = sessile_buffer_host_ptr(s->b[B_LMAX]);
  if (lmax) lmax[0] = 0;
  SESSILE_CALL(sds_gpu_begin(s));
  for (uint32_t k = 0; k < steps; k++) {
    if (lists && k > 0) SESSILE_CALL(sds_gpu_record_lists(s, (s->cur + (int)k) & 1, 0));
    SESSILE_CALL(sds_gpu_record_forces(s, (s->cur + (int)k) & 1, dt, 1, 1, 0));
  }
  SESSILE_CALL(sessile_cmd_end(s->cmd));
  s->flags_cur = -1, s->mirror = -1;
  SESSILE_CALL(sds_gpu_submit(s));
  s->cur = (s->cur + (int)steps) & 1;
  if (lists && steps > 1) {
    lists_invalidate(s); /* built inside the batch: xb is not on the host */
    SESSILE_CHECK(lmax && lmax[0] <= s->lcap, SESSILE_ERR_TOO_LARGE,
                  "sds: a cell had %u contact candidates inside a batch of steps, more than the lists hold (%u): "
                  "use single steps", lmax ? lmax[0] : 0, s->lcap);
  }
  return SESSILE_OK;
}

sessile_status sessile_sds_gpu_forces(sessile_sds_gpu *s, int with_damping, double *f) {
  SESSILE_CALL(run_forces(s, 0.0, with_damping, 0));
  return sessile_buffer_download_reals(s->b[B_F], 0, f, 3 * (size_t)s->ncells);
}

/* One step of mode 1 (dt as given) or 2 (dt capped by the stable bound;
 * B_STEP then holds the step taken, the cap and the bound).  A step that
 * max_move undoes computes the bound again on its retry: 1.7 % of the
 * steps, not worth keeping the bound across submissions. */
static sessile_status step_mode(sessile_sds_gpu *s, double dt, int mode, double *max_move) {
  SESSILE_CALL(run_forces(s, dt, 1, mode));
  s->cur = 1 - s->cur;
  if (s->lists_valid && sds_gpu_contacts_on(s)) { /* still complete at the new x? (radii do not change here) */
    SESSILE_CALL(sessile_buffer_download_reals(s->b[B_MOVE], s->ncells, s->scratch, s->ncells));
    const uint32_t *surf = s->topo_up + s->ntopo_up - 1 - s->nsurf - s->ncells; /* cell_surf (topo's layout: kernels.def) */
    double far = 0, far_surf = 0;
    for (uint32_t c = 0; c < s->ncells; c++) {
      if (!(s->scratch[c] <= far)) far = s->scratch[c];
      if (surf[c] && !(s->scratch[c] <= far_surf)) far_surf = s->scratch[c];
    }
    if (sds_gpu_lists_stale(s, far, far_surf)) lists_invalidate(s);
  }
  if (max_move) {
    SESSILE_CALL(sessile_buffer_download_reals(s->b[B_MOVE], 0, s->scratch, s->ncells));
    double mv = 0;
    for (uint32_t c = 0; c < s->ncells; c++)
      if (!(s->scratch[c] <= mv)) mv = s->scratch[c]; /* NaN propagates */
    *max_move = mv;
  }
  return SESSILE_OK;
}

sessile_status sessile_sds_gpu_step(sessile_sds_gpu *s, double dt, double *max_move) {
  return step_mode(s, dt, 1, max_move);
}

sessile_status sessile_sds_gpu_stable_dt(sessile_sds_gpu *s, double *bound) {
  sds_push p = sds_gpu_push_of(s, 0.0, 1, 2);
  SESSILE_CALL(sds_gpu_begin(s));
  SESSILE_CALL(record_edge(s, s->cur, &p));
  SESSILE_CALL(record_tet(s, s->cur, &p));
  SESSILE_CALL(record_stable(s, &p, s->cur));
  SESSILE_CALL(sessile_cmd_end(s->cmd));
  SESSILE_CALL(sds_gpu_submit(s));
  return sessile_buffer_download_reals(s->b[B_STEP], 2, bound, 1);
}

sessile_status sessile_sds_gpu_advance(sessile_sds_gpu *s, uint32_t steps, double *dt, double *elapsed) {
  const sessile_sds_params *p = &s->p;
  double h = *dt; /* asked for: each step takes min(h, the cap of its state's stable bound) */
  uint32_t done = 0;
  while (done < steps) {
    double mv, hc[2]; /* the step taken, the cap */
    SESSILE_CALL(step_mode(s, h, 2, &mv));
    SESSILE_CALL(sessile_buffer_download_reals(s->b[B_STEP], 0, hc, 2));
    /* the step taken: the one asked when the device took it (an fp32 device
     * returns it rounded to float), else its cap */
    if (hc[0] != dev_real(s, h)) h = hc[0];
    if (!isfinite(mv))
      return sessile_error_set(SESSILE_ERR_NUMERIC, "sds: the state is not finite after a step of %g s (blow-up)", h);
    if (mv > p->max_move) { /* undo: the previous x, v are still in the other pair */
      s->cur = 1 - s->cur;
      h *= 0.5;
      SESSILE_CHECK(h >= p->dt_min, SESSILE_ERR_NUMERIC,
                    "sds: the step fell below dt_min = %g s (a cell moves %g radii per step)", p->dt_min, mv);
      continue;
    }
    done++;
    if (elapsed) *elapsed += h;
    /* the next step: a cell's move grows with the step, so aim the largest
     * at SDS_MOVE_AIM x max_move, growing by at most SDS_GROW a step (the
     * device caps whatever is asked at its bound) */
    double f = mv > 0 ? SDS_MOVE_AIM * p->max_move / mv : SDS_GROW, taken = h;
    h *= f < SDS_GROW ? f : SDS_GROW;
    if (h > p->dt_max) h = p->dt_max;
    SESSILE_CHECK(h >= p->dt_min, SESSILE_ERR_NUMERIC,
                  "sds: the step fell below dt_min = %g s (a cell moved %g radii in a step of %g s)", p->dt_min, mv,
                  taken);
  }
  *dt = h;
  return SESSILE_OK;
}

sessile_status sessile_sds_gpu_inverted(sessile_sds_gpu *s, uint32_t **list, uint32_t *n) {
  *list = NULL, *n = 0;
  if (s->ntets && s->flags_cur != s->cur) { /* not flagged by the step that made this state */
    SESSILE_CALL(sds_gpu_begin(s));
    SESSILE_CALL(sds_gpu_record_inverted(s, s->cur, 0));
    SESSILE_CALL(sessile_cmd_end(s->cmd));
    SESSILE_CALL(sds_gpu_submit(s));
    s->flags_cur = s->cur;
  }
  const uint32_t *flag = sessile_buffer_host_ptr(s->b[B_FLAG]);
  SESSILE_CHECK(flag, SESSILE_ERR_INTERNAL, "sds: the inverted-flag buffer is not mapped");
  uint32_t cnt = 0;
  for (uint32_t t = 0; t < s->ntets; t++) cnt += flag[t] != 0;
  *list = malloc((cnt ? cnt : 1) * sizeof **list);
  SESSILE_CHECK(*list, SESSILE_ERR_NO_MEMORY, "sds: out of memory for %u inverted tets", cnt);
  for (uint32_t t = 0, k = 0; t < s->ntets; t++)
    if (flag[t]) (*list)[k++] = t;
  *n = cnt;
  return SESSILE_OK;
}

void sessile_sds_gpu_list_builds(const sessile_sds_gpu *s, uint64_t *all, uint64_t *partial) {
  *all = s->builds, *partial = s->partial_builds;
}

sessile_status sessile_sds_gpu_hash_table(sessile_sds_gpu *s, uint32_t **table, size_t *n) {
  *table = NULL, *n = 0;
  size_t len = 3 * (size_t)s->tsize + 1 + s->nfaces + 1;
  uint32_t *t = malloc(len * 4);
  SESSILE_CHECK(t, SESSILE_ERR_NO_MEMORY, "sds: out of memory for a hash table of %zu words", len);
  sessile_status st = sessile_buffer_download(s->b[B_HASH], 0, t, len * 4);
  if (st != SESSILE_OK) {
    free(t);
    return st;
  }
  *table = t, *n = len;
  return SESSILE_OK;
}

sessile_status sessile_sds_gpu_time_contacts(sessile_sds_gpu *s, int reps, double *ms_all, double *ms_nocontact,
                                             double *ms_build) {
  *ms_build = 0;
  if (sds_gpu_contacts_on(s)) {
    double t0 = sessile_wall_seconds();
    for (int k = 0; k < reps; k++) {
      lists_invalidate(s);
      SESSILE_CALL(sds_gpu_lists_ensure(s));
    }
    *ms_build = 1e3 * (sessile_wall_seconds() - t0) / (reps > 0 ? reps : 1);
  }
  for (int pass = 0; pass < 2; pass++) {
    s->no_contact = pass;
    SESSILE_CALL(run_forces(s, 0.0, 1, 0)); /* warm-up */
    double t0 = sessile_wall_seconds();
    for (int k = 0; k < reps; k++) {
      sessile_status st = run_forces(s, 0.0, 1, 0);
      if (st != SESSILE_OK) {
        s->no_contact = 0;
        return st;
      }
    }
    *(pass ? ms_nocontact : ms_all) = 1e3 * (sessile_wall_seconds() - t0) / (reps > 0 ? reps : 1);
  }
  s->no_contact = 0;
  return SESSILE_OK;
}
