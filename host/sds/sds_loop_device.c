/* The SDS loop on the device (grow parameter device_loop; docs/sds.md, "The
 * loop on the device"): between topology events the steps run in batches
 * of up to K per submission, each step's rules, morphogens and growth on
 * the device too (sds_gpu_batch_rules.c).  The host wakes at a batch's end:
 * a division asked (it divides, as sds_rules does), a step whose rules are
 * the host's (an inverted tet, more morphogen sub-steps than the batch
 * recorded: it completes that step with the host-driven loop's own code,
 * sds_finish_step), stale contact lists, a frame.  Every step is the
 * host-driven loop's bit for bit on an fp64 device, so the outputs are the
 * same bytes (test sds_device_loop). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sds/sds_gpu_rules.h"
#include "sds/sds_sim.h"
#include "sessile/sds/sds_batch.h"

#define SUB_CAP 16 /* morphogen sub-steps a batch records per step, at most */

sessile_status sds_device_loop_create(sds_sim *s, sessile_gpu *gpu) {
  sds_device_loop_destroy(s);
  sessile_status st = sds_gpu_rules_create_kind(gpu, s->model, s->prm.device_rules, &s->rules_dev);
  if (st == SESSILE_OK)
    st = sds_gpu_rules_set_axial(s->rules_dev, sessile_sds_model_axis(s->model), s->prm.axial_growth,
                                 s->prm.convergent_extension,
                                 sessile_sds_model_state_index(s->model, SDS_STATE_EXTENDING));
  if (st != SESSILE_OK) return sessile_error_set(st, "device_loop: %s", sessile_error_message());
  s->blog = malloc(2 * (size_t)SESSILE_SDS_BATCH_MAX * sizeof *s->blog);
  SESSILE_CHECK(s->blog, SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
  s->rules_sync = 0, s->batch_steps = 16;
  return SESSILE_OK;
}

void sds_device_loop_destroy(sds_sim *s) {
  if (s->pg) sds_gpu_batch_rules(s->pg, NULL, 0);
  sds_gpu_rules_destroy(s->rules_dev);
  free(s->blog);
  s->rules_dev = NULL, s->blog = NULL;
}

/* The device's cells, amounts and states made the host's (after the host
 * changed them: a division, a step it completed, the start). */
static sessile_status sync_device(sds_sim *s) {
  if (s->rules_sync) return SESSILE_OK;
  sessile_morph_cells cells = sds_cells_of(s);
  SESSILE_CALL(sds_gpu_rules_set_cells(s->rules_dev, &cells, s->o.phi, s->o.state, s->density));
  s->rules_sync = 1;
  return SESSILE_OK;
}

/* Sub-steps to record per step: those of twice the next step at today's
 * positions (a step grows by at most 1.25x a step), at most SUB_CAP.
 * Only speed depends on it: a step that needs more is completed by the host. */
static uint32_t sub_steps(const sds_sim *s) {
  if (s->o.nmorph == 0) return 0;
  sessile_morph_cells cells = sds_cells_of(s);
  sessile_morph_coef coef = sessile_sds_model_coef(s->model);
  double bound = sessile_morph_dt_max(&cells, &coef), n = 1;
  if (bound > 0 && isfinite(bound) && 2 * s->dt > bound) n = ceil(2 * s->dt / bound);
  return n < SUB_CAP ? (uint32_t)n : SUB_CAP;
}

/* The divisions the device's rules asked for in the batch's last step. */
static sessile_status divide_requested(sds_sim *s) {
  uint32_t n = s->o.ncells, ev[SDS_EV_COUNT], nreq = 0;
  double *req = malloc((size_t)SDS_REQ * n * sizeof *req);
  sessile_sds_divide *d = malloc((size_t)n * sizeof *d);
  sessile_status st = req && d ? SESSILE_OK : sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
  if (st == SESSILE_OK) st = sds_gpu_rules_read_events(s->rules_dev, ev, req, &nreq);
  for (uint32_t i = 0; st == SESSILE_OK && i < nreq; i++) {
    const double *q = req + (size_t)SDS_REQ * i;
    d[i].cell = (int)q[0], d[i].rule = (int)q[1];
    for (int k = 0; k < 3; k++) d[i].dir[k] = q[2 + k];
  }
  if (st == SESSILE_OK) st = sds_divisions(s, d, nreq);
  free(req), free(d);
  return st;
}

/* One batch, stopping at the first step at or past t_stop at the latest,
 * and what the host does at its end. */
sessile_status sds_device_batch(sds_sim *s, sessile_run *run, double t_stop) {
  sessile_sds_run_stats *t = s->st;
  SESSILE_CALL(sync_device(s));
  uint32_t nsub = sub_steps(s);
  sds_gpu_batch_rules(s->pg, s->rules_dev, nsub);
  double w0 = sessile_wall_seconds(), tb = s->time;
  /* the steps asked: at most those to the stop time at today's step (+1:
   * a step grows; a batch that stops early costs its later steps'
   * dispatches, which return at once but are launched) */
  double to_stop = ceil((t_stop - s->time) / s->dt) + 1;
  uint32_t k = to_stop < s->batch_steps ? (uint32_t)(to_stop > 1 ? to_stop : 1) : s->batch_steps;
  sessile_sds_batch b = {.steps = k, .t_stop = t_stop, .time = s->time, .dt = s->dt, .log = s->blog};
  /* the repairs' backoff table: a step whose inverted tets are its lasting
   * slivers, none due, goes on as the host's loop would let it stand */
  uint32_t pairs[2 * SESSILE_SDS_SLIVERS_MAX], ns = sds_sliver_table(s, pairs);
  if (ns != UINT32_MAX) b.slivers = pairs, b.nslivers = ns;
  s->step_t0 = s->time;
  sessile_status fail = sessile_sds_gpu_batch(s->pg, &b);
  t->batches++;
  uint32_t ev[SDS_EV_COUNT], nreq = 0;
  SESSILE_CALL(sds_gpu_rules_read_events(s->rules_dev, ev, NULL, &nreq));
  uint32_t done = b.done, dev = ev[SDS_EV_LAST]; /* steps whose rules ran on the device */
  sds_gpu_rules_batch_done(s->rules_dev, dev, nsub);
  SESSILE_CHECK(dev <= done && dev + 1 >= done, SESSILE_ERR_INTERNAL,
                "sds: a batch of %u accepted steps made the rules of %u on the device", done, dev);
  /* the slivers the steps kept, counted as the host's loop counts them (a
   * last step the host completes counts its own) */
  t->slivers += b.quiet - (dev < done ? b.quiet_last : 0);
  /* the next batch's size: the last event's distance (a step more), or
   * twice the batch when it ran all its steps; the stop time is no event
   * to learn from.  Only the speed depends on it: a batch's steps are the
   * single steps' */
  if (fail == SESSILE_OK && !(b.events & SESSILE_SDS_EV_TIME))
    s->batch_steps = b.events ? done + 1 : 2 * s->batch_steps;
  if (s->batch_steps > SESSILE_SDS_BATCH_MAX) s->batch_steps = SESSILE_SDS_BATCH_MAX;
  double ms = 1e3 * (sessile_wall_seconds() - w0) / (done ? done : 1);
  /* the steps the device made whole (each row as the host's loop writes it:
   * the time after less the time before); the batch's last one's row
   * after its divisions */
  int last_row = fail == SESSILE_OK && dev == done;
  for (uint32_t j = 0; j < dev; j++) {
    double t0 = s->time;
    s->time = s->blog[2 * j + 1];
    t->steps++, s->steps_frame++;
    s->stalled = 0;
    if (!(last_row && j + 1 == dev)) SESSILE_CALL(sds_steplog_row(s, run, s->time - t0, ms, 0, 0));
  }
  double t_last = dev >= 2 ? s->blog[2 * (dev - 2) + 1] : tb; /* the time before the device's last step */
  s->step_t0 = s->time;
  if (fail != SESSILE_OK) return sds_physics_failed(s, fail);
  s->dt = b.dt;
  if (!done) return SESSILE_OK; /* undone: the next batch retries at half the step */
  SESSILE_CALL(sds_gpu_pull_radii(s->pg));
  SESSILE_CALL(sessile_sds_gpu_download(s->pg, &s->o));
  /* the oriented growth or the extension moved the edges' s_m on the
   * device: the host's copy (divisions, checkpoints and a step the host
   * completes start from it) */
  if (dev && (s->prm.axial_growth != 0 || s->prm.convergent_extension != 0))
    SESSILE_CALL(sessile_sds_gpu_download_edge_sm(s->pg, &s->o));
  if (dev) SESSILE_CALL(sds_gpu_rules_get_cells(s->rules_dev, s->o.phi, s->o.state));
  uint64_t d0 = t->divisions, i0 = t->inversions;
  if (dev < done) { /* the last step's rules are the host's: it completes the step as its own loop does */
    free(s->xprev);
    s->xprev = malloc((size_t)s->o.ncells * 3 * sizeof *s->xprev);
    SESSILE_CHECK(s->xprev, SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
    SESSILE_CALL(sds_gpu_download_prev_x(s->pg, s->xprev));
    double t0 = s->time;
    s->rules_sync = 0;
    t->host_steps++;
    SESSILE_CALL(sds_finish_step(s, s->blog[2 * (done - 1)]));
    return sds_steplog_row(s, run, s->time - t0, ms, t->divisions - d0, t->inversions - i0);
  }
  SESSILE_CALL(sds_check_motion(s));
  if (ev[SDS_EV_FLAGS] & 2u)
    return sds_blowup(s, "a rule gave cell %u a value that is not finite (a runaway growth or production?)",
                      ev[SDS_EV_BAD]);
  if (ev[SDS_EV_FLAGS] & 1u) {
    SESSILE_CALL(divide_requested(s));
    s->rules_sync = 0;
  }
  SESSILE_CALL(sds_refresh(s)); /* as the host's rules end: the radii up, the lists' growth checked */
  SESSILE_CALL(sds_check_cells(s));
  return sds_steplog_row(s, run, s->time - t_last, ms, t->divisions - d0, t->inversions - i0);
}
